#pragma once
// The schema of a parameter struct: for every field its key, range, unit and one-line meaning,
// declared once beside the struct (the default is the field's initializer). Validation, the ROS
// node's YAML reader, the CLI's options, config/default.yaml and docs/parameters.md all come from
// it, so a parameter is added in one place.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace stocs {

/// The allowed values of a numeric parameter: an interval whose ends may be open, and optionally
/// one value outside it with a meaning of its own (0: "off").
struct ParamRange {
  double lo = 0, hi = 0;
  bool lo_open = false, hi_open = false;
  std::optional<double> also;

  static ParamRange closed(double lo, double hi) { return make(lo, hi, false, false); }
  /// (lo, hi]
  static ParamRange aboveUpTo(double lo, double hi) { return make(lo, hi, true, false); }
  /// [lo, hi)
  static ParamRange fromBelow(double lo, double hi) { return make(lo, hi, false, true); }
  ParamRange orAlso(double value) const {
    ParamRange r = *this;
    r.also = value;
    return r;
  }

  /// False for NaN. `in_float`: compare as a float field holds values, so that a float field set
  /// to a bound's decimal (0.1) is at the bound, not a rounding step past it.
  bool contains(double v, bool in_float = false) const;
  std::string str() const;  ///< "[1, 1000]", "(0, 0.1]", "0 or [1, 100]"

 private:
  static ParamRange make(double lo, double hi, bool lo_open, bool hi_open) {
    ParamRange r;
    r.lo = lo;
    r.hi = hi;
    r.lo_open = lo_open;
    r.hi_open = hi_open;
    return r;
  }
};

/// A string parameter's value held as an enum (or anything else) in the struct.
struct ChoiceRef {
  std::function<std::string()> get;
  std::function<void(const std::string&)> set;
};

/// One field of a parameter struct, as the schema reaches it.
using ParamRef = std::variant<bool*, int*, float*, double*, uint64_t*, std::string*,
                              std::vector<std::string>*, std::vector<int>*, ChoiceRef>;

/// What a schema says of one parameter.
struct ParamInfo {
  std::string key;                   ///< dotted path from the schema's root: "icp.iterations"
  std::string meaning;               ///< one line
  std::string unit;                  ///< "m", "deg", "s", or empty
  std::optional<ParamRange> range;   ///< numbers: the allowed values (none: any)
  std::vector<std::string> choices;  ///< strings: the allowed values (empty: any)
  std::string flag;   ///< the CLI option ("--bases"); empty: flagFor() derives one from the key
  std::string group;  ///< heading of the part of the root it belongs to (CLI help, docs)

  /// The CLI option: `flag`, else "--" and the key with '.' and '_' as '-'.
  std::string cliFlag() const;
  /// "0 is outside [1, 1000]" (with the unit after the value), or nothing when `value` is allowed.
  std::optional<std::string> problem(const ParamRef& value) const;
};

/// The schema of the parameter struct S: its fields in order, each with a ParamInfo and a way to
/// reach the field, with the schemas of nested structs flattened into it under their key.
template <class S>
class ParamSet {
 public:
  struct Entry {
    ParamInfo info;
    std::function<ParamRef(S&)> field;
  };

  /// A number or a flag.
  template <class T>
  ParamSet& add(T S::*member, std::string key, std::string unit, std::optional<ParamRange> range,
                std::string meaning) {
    ParamInfo info;
    info.key = std::move(key);
    info.unit = std::move(unit);
    info.range = range;
    info.meaning = std::move(meaning);
    entries_.push_back({std::move(info), [member](S& s) -> ParamRef { return &(s.*member); }});
    return *this;
  }
  ParamSet& add(bool S::*member, std::string key, std::string meaning) {
    return add(member, std::move(key), "", std::nullopt, std::move(meaning));
  }
  /// A string with a fixed set of values, held in the struct as E (an enum).
  template <class E>
  ParamSet& choice(E S::*member, std::string key, std::vector<std::pair<std::string, E>> values,
                   std::string meaning);
  /// The CLI option of the last parameter added, where its derived name would be unwieldy.
  ParamSet& flag(std::string name) {
    entries_.back().info.flag = std::move(name);
    return *this;
  }
  /// Every parameter of `sub` under `key`, reached through `member`; `group` heads them.
  template <class Sub>
  ParamSet& nest(Sub S::*member, const std::string& key, const ParamSet<Sub>& sub,
                 const std::string& group = "");

  const std::vector<Entry>& entries() const { return entries_; }

  /// Throws InputError "<name> <problem>" for the first parameter out of range, its name as
  /// `name` gives it (default: its key).
  void validate(
      const S& s, const std::function<std::string(const ParamInfo&)>& name =
                      [](const ParamInfo& info) { return info.key; }) const;

  /// Every parameter with its value in `s` as text ("0.005", "true", "cloud"), for the docs.
  std::vector<std::pair<ParamInfo, std::string>> describe(const S& s) const {
    std::vector<std::pair<ParamInfo, std::string>> out;
    S& fields = const_cast<S&>(s);  // only read
    for (const Entry& e : entries_) out.emplace_back(e.info, paramText(e.field(fields)));
    return out;
  }

 private:
  std::vector<Entry> entries_;
};

/// The value a reference holds, as text ("0.005", "true", "cloud").
std::string paramText(const ParamRef& value);

/// Throws InputError "<name> <problem>" when `problem` holds one.
void throwParamProblem(const std::string& name, const std::optional<std::string>& problem);

template <class S>
template <class E>
ParamSet<S>& ParamSet<S>::choice(E S::*member, std::string key,
                                 std::vector<std::pair<std::string, E>> values,
                                 std::string meaning) {
  ParamInfo info;
  info.key = std::move(key);
  info.meaning = std::move(meaning);
  for (const auto& v : values) info.choices.push_back(v.first);
  auto field = [member, values](S& s) -> ParamRef {
    E* e = &(s.*member);
    return ChoiceRef{[e, values] {
                       for (const auto& v : values) {
                         if (v.second == *e) return v.first;
                       }
                       return std::string();
                     },
                     [e, values](const std::string& name) {
                       for (const auto& v : values) {
                         if (v.first == name) *e = v.second;
                       }
                     }};
  };
  entries_.push_back({std::move(info), field});
  return *this;
}

template <class S>
template <class Sub>
ParamSet<S>& ParamSet<S>::nest(Sub S::*member, const std::string& key, const ParamSet<Sub>& sub,
                               const std::string& group) {
  for (const auto& e : sub.entries()) {
    ParamInfo info = e.info;
    info.key = key + "." + info.key;
    if (!group.empty()) info.group = group;
    auto inner = e.field;
    entries_.push_back({std::move(info), [member, inner](S& s) { return inner(s.*member); }});
  }
  return *this;
}

template <class S>
void ParamSet<S>::validate(const S& s,
                           const std::function<std::string(const ParamInfo&)>& name) const {
  S& fields = const_cast<S&>(s);  // the accessors give mutable references; only read here
  for (const Entry& e : entries_) throwParamProblem(name(e.info), e.info.problem(e.field(fields)));
}

}  // namespace stocs
