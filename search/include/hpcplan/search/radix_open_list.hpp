#pragma once
// A monotone open list (a radix heap, Ahuja, Mehlhorn, Orlin and Tarjan 1990) for searches
// whose priorities never fall below the last one popped: A* with a consistent heuristic and
// exact costs, Dijkstra. A push costs O(1) (no sift). Entries are only sorted again when the
// entries equal to the last key run out, and each entry moves down at most 63 times in its
// life. On a 2D query the binary heap's pop was half of the search's time.
//
// Keys are the bits of the priority: non-negative doubles order the same as their bit
// patterns read as unsigned integers. Bucket b (1..63) holds the entries whose key first
// differs from the last popped key at bit b-1; the entries equal to it wait in `equal_`.
//
// Among equal priorities the order is the binary heap's: deepest (largest g) first, and among
// equal g the oldest first. Both matter on the lattice's plateaus: popping the newest instead
// (a stack) expanded 19x more states on a dense 4D field.
//
// Monotonicity is the caller's promise. push() reports a broken one (a key below the last
// popped, or a negative priority) by returning false and storing nothing. The caller keeps such
// entries elsewhere (SearchStore: in a binary heap popped before this list) rather than return
// a wrong answer.
//
// Threads: one list belongs to one search on one thread.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "hpcplan/core/idle_pool.hpp"

namespace hpcplan::search {

// Entries of one priority, deepest first, oldest first among equal g. A search pushes here only
// the children of the entry it just popped, which was the deepest: a child is deeper than
// everything waiting, or as deep as the newest group. So the deepest group is a FIFO
// (`top_`), and the rest (`below_`, sorted by g, next to pop at the back) only grows when a
// deeper group displaces it. Each entry is moved at most once that way.
template <class Entry>
class EqualPriorityQueue {
 public:
  [[gnu::always_inline]] void push(const Entry& e) {
    if (head_ == top_.size()) {
      // No deepest group waits: e starts one, unless it is no deeper than what waits below
      // (not what a search pushes, but kept correct).
      if (!below_.empty() && e.g <= below_.back().g) {
        insert_below(e);
        return;
      }
      top_.clear();
      head_ = 0;
    } else if (e.g > top_.back().g) {
      move_top_below();  // a deeper group starts
    } else if (e.g < top_.back().g) {
      insert_below(e);
      return;
    }
    top_.push_back(e);
  }
  // The next entry; the queue must not be empty.
  [[gnu::always_inline]] Entry pop() {
    if (head_ < top_.size()) return top_[head_++];
    const Entry e = below_.back();
    below_.pop_back();
    return e;
  }
  const Entry& next() const { return head_ < top_.size() ? top_[head_] : below_.back(); }
  bool empty() const { return head_ == top_.size() && below_.empty(); }
  // Refilled from entries of one priority in no particular order: sorted by g only.
  void assign(std::vector<Entry>& from) {
    below_.swap(from);
    from.clear();
    std::sort(below_.begin(), below_.end(),
              [](const Entry& a, const Entry& b) { return a.g < b.g; });
    top_.clear();
    head_ = 0;
  }
  template <class Sink>
  void for_each(Sink& sink) const {
    for (std::size_t i = head_; i < top_.size(); ++i) sink(top_[i]);
    for (const Entry& e : below_) sink(e);
  }
  void clear() {
    top_.clear();
    below_.clear();
    head_ = 0;
  }
  std::size_t capacity() const { return top_.capacity() + below_.capacity(); }

 private:
  // The group waiting at the top (oldest first) goes below it, under the same order.
  void move_top_below() {
    for (std::size_t i = top_.size(); i > head_; --i) below_.push_back(top_[i - 1]);
    top_.clear();
    head_ = 0;
  }
  // The entries waiting below keep g ascending, the oldest of equal g at the back.
  [[gnu::noinline]] void insert_below(const Entry& e) {
    std::size_t at = below_.size();
    while (at > 0 && !(below_[at - 1].g < e.g)) --at;
    below_.insert(below_.begin() + static_cast<std::ptrdiff_t>(at), e);
  }

  std::vector<Entry> top_;  // the deepest group, FIFO from head_
  std::size_t head_ = 0;
  std::vector<Entry> below_;
};

template <class Entry>
class RadixOpenList {
 public:
  // False (and nothing stored) when e's priority is negative or below the last popped one.
  [[gnu::always_inline]] bool push(const Entry& e) {
    const std::uint64_t k = key(e);
    if (k < last_ || (k >> 63) != 0) return false;
    if (k == last_)
      equal_.push(e);
    else
      place(e, k);
    ++size_;
    return true;
  }

  // Takes an entry of least priority off the list; false when empty.
  [[gnu::always_inline]] bool pop(Entry& out) {
    if (size_ == 0) return false;
    if (equal_.empty()) refill();
    out = equal_.pop();
    --size_;
    return true;
  }

  // The least priority stored; false when empty. O(bucket) when no entry equals the last key.
  bool least(double& f) const {
    if (size_ == 0) return false;
    if (!equal_.empty()) {
      f = equal_.next().f;
      return true;
    }
    const auto& lowest = buckets_[std::countr_zero(occupied_)];
    f = std::min_element(lowest.begin(), lowest.end(), by_key)->f;
    return true;
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  void clear() {
    for (auto& b : buckets_) b.clear();
    equal_.clear();
    occupied_ = 0;
    last_ = 0;  // a cleared list starts over (the pool lends it to the next search)
    size_ = 0;
  }
  std::size_t capacity_bytes() const {
    std::size_t n = refilled_.capacity() + equal_.capacity();
    for (const auto& b : buckets_) n += b.capacity();
    return n * sizeof(Entry);
  }

 private:
  static std::uint64_t key(const Entry& e) { return std::bit_cast<std::uint64_t>(e.f); }
  static bool by_key(const Entry& a, const Entry& b) { return key(a) < key(b); }

  // Into the bucket of the highest bit where k differs from the last key (k != last_).
  [[gnu::always_inline]] void place(const Entry& e, std::uint64_t k) {
    const int b = 64 - std::countl_zero(k ^ last_);
    buckets_[b].push_back(e);
    occupied_ |= std::uint64_t{1} << b;
  }

  // Nothing equals the last key: the least key lives in the lowest occupied bucket. It becomes
  // the new last key, and that bucket's entries move to lower buckets or to `equal_` (each
  // lands below b, since the entries agree with the new key above bit b-1).
  void refill() {
    const int b = std::countr_zero(occupied_);
    std::vector<Entry>& from = buckets_[b];
    last_ = key(*std::min_element(from.begin(), from.end(), by_key));
    for (const Entry& e : from) {
      const std::uint64_t k = key(e);
      if (k == last_)
        refilled_.push_back(e);
      else
        place(e, k);
    }
    from.clear();
    occupied_ &= ~(std::uint64_t{1} << b);
    equal_.assign(refilled_);
  }

  // buckets_[0] stays empty (those entries are in equal_): the index is the bit position + 1.
  std::array<std::vector<Entry>, 64> buckets_;
  EqualPriorityQueue<Entry> equal_;
  std::vector<Entry> refilled_;  // scratch for refill, kept for its capacity
  std::uint64_t occupied_ = 0;   // bit b: buckets_[b] non-empty
  std::uint64_t last_ = 0;
  std::size_t size_ = 0;
};

// Lends lists to searches and takes them back emptied, with their vectors' capacity (see
// IdlePool: a warm 8D OMPL query took 8 ms instead of 2.9 while every search allocated its
// own). A list that grew past kKeepBytes is freed rather than kept.
//
// Threads: the pool may be used from any thread; a lent list belongs to one search.
template <class Entry>
class LentOpenList {
 public:
  LentOpenList() = default;
  LentOpenList(const LentOpenList&) = delete;
  LentOpenList& operator=(const LentOpenList&) = delete;
  ~LentOpenList() { give_back(); }

  void borrow() {
    give_back();
    list_ = IdlePool<RadixOpenList<Entry>>::take();
    if (!list_) list_ = std::make_unique<RadixOpenList<Entry>>();
  }
  explicit operator bool() const { return list_ != nullptr; }
  RadixOpenList<Entry>* operator->() const { return list_.get(); }

  static constexpr std::size_t kKeepBytes = std::size_t{64} << 20;

 private:
  void give_back() {
    if (!list_) return;
    list_->clear();
    if (list_->capacity_bytes() <= kKeepBytes)
      IdlePool<RadixOpenList<Entry>>::keep(std::move(list_));
    list_.reset();
  }

  std::unique_ptr<RadixOpenList<Entry>> list_;
};

}  // namespace hpcplan::search
