// Parameter structs <-> JSON, driven by each struct's static `visit(self, visitor)` field list,
// so the list of names is written once per struct. Reading is strict: a parameter that the
// struct does not have, or a value of the wrong type, is an InputError naming the field, so a
// typo in a replay command cannot silently fall back to a default.
#pragma once

#include <climits>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "core/errors.hpp"

namespace cullcheck::generators {

template <class Params>
nlohmann::json params_to_json(const Params& p) {
  nlohmann::json j = nlohmann::json::object();
  Params::visit(p, [&](const char* name, const auto& field) { j[name] = field; });
  return j;
}

namespace detail {

inline void read_field(const nlohmann::json& v, int& field, const std::string& object, const std::string& name,
                       const std::string& owner) {
  if (!v.is_number_integer() || v.get<long long>() < INT_MIN || v.get<long long>() > INT_MAX)
    throw InputError(object, name, owner + ": must be an integer (got " + v.dump() + ")");
  field = static_cast<int>(v.get<long long>());
}

inline void read_field(const nlohmann::json& v, double& field, const std::string& object, const std::string& name,
                       const std::string& owner) {
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    throw InputError(object, name, owner + ": must be a finite number (got " + v.dump() + ")");
  field = v.get<double>();
}

inline void read_field(const nlohmann::json& v, std::string& field, const std::string& object, const std::string& name,
                       const std::string& owner) {
  if (!v.is_string()) throw InputError(object, name, owner + ": must be a string (got " + v.dump() + ")");
  field = v.get<std::string>();
}

inline void read_field(const nlohmann::json& v, bool& field, const std::string& object, const std::string& name,
                       const std::string& owner) {
  if (!v.is_boolean()) throw InputError(object, name, owner + ": must be true or false (got " + v.dump() + ")");
  field = v.get<bool>();
}

}  // namespace detail

// Overlays the members of the JSON object `j` on `p`. `object` is the InputError object name
// ("generator", "path"); `owner` (the generator or path kind) prefixes the problem text.
template <class Params>
void overlay_params_json(Params& p, const nlohmann::json& j, const std::string& object, const std::string& owner) {
  if (j.is_null()) return;
  if (!j.is_object()) throw InputError(object, "params", owner + ": parameters must be a JSON object (got " + j.dump() + ")");
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool found = false;
    Params::visit(p, [&](const char* name, auto& field) {
      if (found || it.key() != name) return;
      found = true;
      detail::read_field(it.value(), field, object, name, owner);
    });
    if (!found) {
      std::string known;
      Params::visit(p, [&](const char* name, auto&) { known += (known.empty() ? "" : ", ") + std::string(name); });
      throw InputError(object, it.key(), owner + ": unknown parameter (known: " + known + ")");
    }
  }
}

}  // namespace cullcheck::generators
