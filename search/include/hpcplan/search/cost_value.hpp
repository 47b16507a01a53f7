#pragma once
// A cost as a double, for any graph's cost type: plain doubles, or exact cost types that know
// their own value() (the lattice's LatticeCost). The engine needs nothing else of a cost type
// beyond +, == and default construction.
namespace hpcplan {

template <class Cost>
double cost_value(const Cost& c) {
  if constexpr (requires { c.value(); })
    return c.value();
  else
    return static_cast<double>(c);
}

}  // namespace hpcplan
