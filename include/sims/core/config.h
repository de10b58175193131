// Config structs bound to JSON (Drake style): a plain struct with defaults lists its fields in
// `template <class A> void Serialize(A* a)` via SIMS_NVP, may add `void Validate() const`
// (throwing FieldError through Require), and is loaded/saved/round-tripped by these helpers.
//
//   struct PpoConfig {
//     double clip = 0.2;
//     template <class A> void Serialize(A* a) { a->Visit(SIMS_NVP(clip)); }
//     void Validate() const { Require(clip > 0, "clip", "a positive number"); }
//   };
//   auto cfg = LoadConfig<PpoConfig>("configs/ppo.json");
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "sims/core/error.h"

namespace sims {

/// A named pointer to a config field, produced by SIMS_NVP.
template <typename T>
struct NameValue {
  const char* name;  ///< JSON key.
  T* value;          ///< Field to read or write.
};

/// Builds a NameValue (used by the SIMS_NVP macro).
template <typename T>
NameValue<T> MakeNameValue(const char* name, T* value) {
  return {name, value};
}

}  // namespace sims

/// Names a struct member for Serialize(): a->Visit(SIMS_NVP(field)).
#define SIMS_NVP(member) ::sims::MakeNameValue(#member, &member)

namespace sims {
namespace config_internal {

template <typename T, typename = void>
struct IsSerializable : std::false_type {};
struct ProbeArchive {
  template <typename U>
  void Visit(const NameValue<U>&) {}
  template <typename U>
  void VisitRenamed(const char*, const NameValue<U>&) {}
};
template <typename T>
struct IsSerializable<
    T, std::void_t<decltype(std::declval<T&>().Serialize(std::declval<ProbeArchive*>()))>>
    : std::true_type {};

template <typename T, typename = void>
struct HasValidate : std::false_type {};
template <typename T>
struct HasValidate<T, std::void_t<decltype(std::declval<const T&>().Validate())>> : std::true_type {
};

template <typename T>
struct IsVector : std::false_type {};
template <typename T, typename A>
struct IsVector<std::vector<T, A>> : std::true_type {};
template <typename T>
struct IsArray : std::false_type {};
template <typename T, std::size_t N>
struct IsArray<std::array<T, N>> : std::true_type {};
template <typename T>
struct IsStringMap : std::false_type {};
template <typename T>
struct IsStringMap<std::map<std::string, T>> : std::true_type {};
template <typename T>
struct IsOptional : std::false_type {};
template <typename T>
struct IsOptional<std::optional<T>> : std::true_type {};

std::string JsonTypeName(const nlohmann::json& j);
std::string Abbreviate(const nlohmann::json& j);

}  // namespace config_internal

/// Runs `value.Validate()` if the type has one (and recurses nowhere: nested structs are
/// validated by the read archive as they are visited).
template <typename T>
void ValidateIfPossible(const T& value) {
  if constexpr (config_internal::HasValidate<T>::value) value.Validate();
}

/// Reads fields from JSON into a struct; unknown keys, wrong types and failed validation
/// throw FieldError with the dotted field path.
class JsonReadArchive {
 public:
  /// `j` must outlive the archive; `allow_unknown` skips the unknown-key check.
  explicit JsonReadArchive(const nlohmann::json& j, bool allow_unknown = false)
      : j_(j), allow_unknown_(allow_unknown) {}

  /// Reads one field if present (absent keys keep their defaults).
  template <typename T>
  void Visit(const NameValue<T>& nv) {
    seen_.insert(nv.name);
    if (!j_.is_object()) return;
    auto it = j_.find(nv.name);
    if (it == j_.end()) return;
    try {
      Read(*it, nv.value);
    } catch (const FieldError& e) {
      throw e.WithPrefix(nv.name);
    }
  }

  /// Reads a field's former name `old_name` into nv (files written before the rename); giving
  /// both names is an error. Call it after Visit(nv).
  template <typename T>
  void VisitRenamed(const char* old_name, const NameValue<T>& nv) {
    seen_.insert(old_name);
    if (!j_.is_object() || !j_.contains(old_name)) return;
    if (j_.contains(nv.name))
      throw FieldError(old_name, std::string("only its new name '") + nv.name + "'", "both names");
    Visit(MakeNameValue(old_name, nv.value));
  }

  /// Copies every key no Visit() has named so far into `rest` (an object) and counts them as
  /// known: a struct whose remaining keys belong to a plugin (a registered skill's params)
  /// visits them last and has its Validate() check them.
  void VisitRest(nlohmann::json* rest) {
    *rest = nlohmann::json::object();
    if (!j_.is_object()) return;
    for (auto it = j_.begin(); it != j_.end(); ++it)
      if (!seen_.count(it.key())) (*rest)[it.key()] = it.value();
    for (auto it = rest->begin(); it != rest->end(); ++it) seen_.insert(it.key());
  }

  /// Throws on keys that no Visit() named.
  void CheckNoUnknownKeys() const;

  /// Reads a whole value of any supported type (entry point and recursion).
  template <typename T>
  static void Read(const nlohmann::json& j, T* out, bool allow_unknown = false) {
    using config_internal::JsonTypeName;
    if constexpr (config_internal::IsSerializable<T>::value) {
      if (!j.is_object()) throw FieldError("", "an object", JsonTypeName(j));
      JsonReadArchive sub(j, allow_unknown);
      out->Serialize(&sub);
      sub.CheckNoUnknownKeys();
      ValidateIfPossible(*out);
    } else if constexpr (config_internal::IsOptional<T>::value) {
      if (j.is_null()) {
        out->reset();
      } else {
        typename T::value_type v{};
        Read(j, &v, allow_unknown);
        *out = std::move(v);
      }
    } else if constexpr (config_internal::IsVector<T>::value) {
      if (!j.is_array()) throw FieldError("", "an array", JsonTypeName(j));
      T result(j.size());
      for (std::size_t i = 0; i < j.size(); ++i) {
        try {
          Read(j[i], &result[i], allow_unknown);
        } catch (const FieldError& e) {
          throw e.WithPrefix("[" + std::to_string(i) + "]");
        }
      }
      *out = std::move(result);
    } else if constexpr (config_internal::IsArray<T>::value) {
      if (!j.is_array() || j.size() != out->size())
        throw FieldError("", "an array of " + std::to_string(out->size()) + " values",
                         config_internal::Abbreviate(j));
      for (std::size_t i = 0; i < out->size(); ++i) {
        try {
          Read(j[i], &(*out)[i], allow_unknown);
        } catch (const FieldError& e) {
          throw e.WithPrefix("[" + std::to_string(i) + "]");
        }
      }
    } else if constexpr (config_internal::IsStringMap<T>::value) {
      if (!j.is_object()) throw FieldError("", "an object", JsonTypeName(j));
      T result;
      for (auto it = j.begin(); it != j.end(); ++it) {
        try {
          Read(it.value(), &result[it.key()], allow_unknown);
        } catch (const FieldError& e) {
          throw e.WithPrefix(it.key());
        }
      }
      *out = std::move(result);
    } else if constexpr (std::is_same_v<T, bool>) {
      if (!j.is_boolean()) throw FieldError("", "true or false", config_internal::Abbreviate(j));
      *out = j.get<bool>();
    } else if constexpr (std::is_integral_v<T>) {
      if (!j.is_number_integer())
        throw FieldError("", "an integer", config_internal::Abbreviate(j));
      if constexpr (std::is_unsigned_v<T>) {
        if (j.is_number_integer() && !j.is_number_unsigned() && j.get<int64_t>() < 0)
          throw FieldError("", "a non-negative integer", config_internal::Abbreviate(j));
      }
      *out = j.get<T>();
    } else if constexpr (std::is_floating_point_v<T>) {
      if (!j.is_number()) throw FieldError("", "a number", config_internal::Abbreviate(j));
      *out = j.get<T>();
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (!j.is_string()) throw FieldError("", "a string", config_internal::Abbreviate(j));
      *out = j.get<std::string>();
    } else if constexpr (std::is_enum_v<T>) {
      static_assert(sizeof(T) == 0, "enums in configs are strings; convert in Validate()");
    } else {
      static_assert(sizeof(T) == 0, "unsupported config field type");
    }
  }

 private:
  const nlohmann::json& j_;
  bool allow_unknown_;
  std::set<std::string> seen_;
};

/// Writes a struct's fields into JSON.
class JsonWriteArchive {
 public:
  /// Writes into `j` (which becomes an object).
  explicit JsonWriteArchive(nlohmann::json* j) : j_(j) { *j_ = nlohmann::json::object(); }

  /// Writes one field.
  template <typename T>
  void Visit(const NameValue<T>& nv) {
    (*j_)[nv.name] = Write(*nv.value);
  }

  /// Former names are read only: the field is written under its new name.
  template <typename T>
  void VisitRenamed(const char*, const NameValue<T>&) {}

  /// Writes the keys of `rest` beside the named fields (VisitRest's read side); a named field
  /// wins over a rest key of the same name.
  void VisitRest(const nlohmann::json* rest) {
    for (auto it = rest->begin(); it != rest->end(); ++it)
      if (!j_->contains(it.key())) (*j_)[it.key()] = it.value();
  }

  /// Converts any supported value to JSON.
  template <typename T>
  static nlohmann::json Write(const T& v) {
    if constexpr (config_internal::IsSerializable<T>::value) {
      nlohmann::json j;
      JsonWriteArchive sub(&j);
      const_cast<T&>(v).Serialize(&sub);
      return j;
    } else if constexpr (config_internal::IsOptional<T>::value) {
      return v ? Write(*v) : nlohmann::json(nullptr);
    } else if constexpr (config_internal::IsVector<T>::value ||
                         config_internal::IsArray<T>::value) {
      nlohmann::json j = nlohmann::json::array();
      for (const auto& e : v) j.push_back(Write(e));
      return j;
    } else if constexpr (config_internal::IsStringMap<T>::value) {
      nlohmann::json j = nlohmann::json::object();
      for (const auto& [k, e] : v) j[k] = Write(e);
      return j;
    } else {
      return nlohmann::json(v);
    }
  }

 private:
  nlohmann::json* j_;
};

/// Converts a config struct to JSON.
template <typename T>
nlohmann::json ConfigToJson(const T& config) {
  return JsonWriteArchive::Write(config);
}

/// Parses a config struct from JSON, starting from `defaults`; `source` names the origin in
/// errors (a file path or "--flag").
template <typename T>
T ConfigFromJson(const nlohmann::json& j, const std::string& source, T defaults = T{}) {
  try {
    JsonReadArchive::Read(j, &defaults);
  } catch (const FieldError& e) {
    ThrowInputError(source, e.field(), e.expected(), e.got());
  }
  return defaults;
}

/// Reads a JSON file; parse errors name the file, line and column.
nlohmann::json ReadJsonFile(const std::filesystem::path& path);

/// Loads a config struct from a JSON file (missing keys keep defaults).
template <typename T>
T LoadConfig(const std::filesystem::path& path, T defaults = T{}) {
  return ConfigFromJson<T>(ReadJsonFile(path), path.string(), std::move(defaults));
}

/// Validates a config built in code; errors name `source`.
template <typename T>
void ValidateConfig(const T& config, const std::string& source) {
  // A write/read round trip runs the validators of nested structs too.
  (void)ConfigFromJson<T>(ConfigToJson(config), source);
}

/// Writes text to `path` atomically (temp file in the same folder, then rename).
void WriteFileAtomic(const std::filesystem::path& path, const std::string& content);

/// Writes JSON (indented) atomically.
void WriteJsonFile(const std::filesystem::path& path, const nlohmann::json& j);

/// Saves a config struct as indented JSON, atomically.
template <typename T>
void SaveConfig(const std::filesystem::path& path, const T& config) {
  WriteJsonFile(path, ConfigToJson(config));
}

}  // namespace sims
