#include "hpcplan/cli/option_catalog.hpp"

#include <sstream>

namespace hpcplan::cli {

namespace {

// The validators' descriptions follow the type in CLI11's type name ("UINT:[2, 65535]",
// "TEXT:{auto,dense,sparse}"); number_options.hpp names its own validator "number".
void read_validators(const std::string& type_name, OptionInfo& info) {
  std::size_t at = type_name.find(':');
  while (at != std::string::npos) {
    const std::size_t next = type_name.find(':', at + 1);
    const std::string part =
        type_name.substr(at + 1, next == std::string::npos ? next : next - at - 1);
    if (part.size() >= 2 && part.front() == '[' && part.back() == ']') info.range = part;
    if (part.size() >= 2 && part.front() == '{' && part.back() == '}') {
      std::stringstream items(part.substr(1, part.size() - 2));
      for (std::string item; std::getline(items, item, ',');) info.choices.push_back(item);
    }
    at = next;
  }
}

std::string kind_of(const CLI::Option& o, const std::string& type_name) {
  if (o.get_expected_max() == 0) return "flag";  // takes no value
  const std::string base = type_name.substr(0, type_name.find(':'));
  const bool list = o.get_items_expected_max() > 1;
  if (base == "INT" || base == "UINT") return list ? "int_list" : "int";
  if (base == "FLOAT") return list ? "float_list" : "float";
  return "text";
}

}  // namespace

std::vector<OptionInfo> describe_options(const CLI::App& command) {
  std::vector<OptionInfo> out;
  for (const CLI::Option* o : command.get_options()) {
    if (o == command.get_help_ptr() || o->get_lnames().empty()) continue;
    OptionInfo info;
    info.option = "--" + o->get_lnames().front();
    info.name = o->get_lnames().front();
    for (char& c : info.name)
      if (c == '-') c = '_';
    const std::string type_name = o->get_type_name();
    info.kind = kind_of(*o, type_name);
    info.default_text = o->get_default_str();
    info.required = o->get_required();
    read_validators(type_name, info);
    info.help = o->get_description();
    info.group = o->get_group();
    out.push_back(std::move(info));
  }
  return out;
}

}  // namespace hpcplan::cli
