// The contract's JSON reader and writer, its name tables and its resolution.
#include "oblique/cases/contract.h"

#include <cmath>

#include <algorithm>
#include <iterator>

#include "oblique/protocol/json.h"
#include "oblique/protocol/names.h"

namespace oblique {

namespace {

using cases::Property;
using cases::StatusContract;
using protocol::JsonValue;

/// A contract file is a few lines; anything larger is not one.
constexpr std::size_t kMaxContractBytes = 1u << 20;

template <class E>
bool contains(const std::vector<E>& list, E value) {
  return std::find(list.begin(), list.end(), value) != list.end();
}

/// The JSON fields of a contract, in the writer's order.
const std::vector<std::string>& field_names() {
  static const std::vector<std::string> names = {
      "preset",   "families", "conventions", "places",        "planes",
      "statuses", "defects",  "properties",  "row3_accuracy", "exclude"};
  return names;
}

/// Reads a list of names with `parse` into `out`, which it replaces; false with `error`.
template <class E, class Parse>
bool read_names(const JsonValue& v, const char* field, const char* what, Parse parse,
                const std::vector<std::string>& known, std::vector<E>& out, std::string& error) {
  if (!v.is(JsonValue::Kind::array)) {
    error = std::string("\"") + field + "\" is a list of names, not " + protocol::kind_name(v.kind);
    return false;
  }
  std::vector<E> read;
  for (const JsonValue& item : v.items) {
    if (!item.is(JsonValue::Kind::string)) {
      error = std::string("\"") + field + "\" holds names, not " + protocol::kind_name(item.kind);
      return false;
    }
    const auto value = parse(item.text);
    if (!value) {
      error = "\"" + std::string(field) + "\": " + protocol::unknown_name(what, item.text, known);
      return false;
    }
    if (!contains(read, *value)) read.push_back(*value);
  }
  out = std::move(read);
  return true;
}

template <class E, class Name>
std::string json_names(const std::vector<E>& list, Name name) {
  std::string out = "[";
  for (const E& e : list) out += (out.size() > 1 ? ", " : "") + protocol::json_string(name(e));
  return out + "]";
}

std::optional<Status> parse_refusal(std::string_view name) {
  const auto status = parse_status(name);
  if (!status || *status == Status::ok) return std::nullopt;
  return status;
}

}  // namespace

std::optional<Property> parse_property(std::string_view name) noexcept {
  for (Property p : cases::Checks{}.properties) {
    if (cases::property_name(p) == name) return p;
  }
  return std::nullopt;
}

std::vector<std::string> property_names() {
  std::vector<std::string> out;
  for (Property p : cases::Checks{}.properties) out.emplace_back(cases::property_name(p));
  return out;
}
std::vector<std::string> refusal_names() {
  std::vector<std::string> out;
  for (Status s : all_statuses) {
    if (s != Status::ok) out.emplace_back(status_code(s));
  }
  return out;
}

Contract resolved(Contract c, const std::vector<Convention>& own_conventions,
                  StatusContract own_statuses, bool own_row3_accuracy) {
  if (!c.row3_accuracy) c.row3_accuracy = own_row3_accuracy;
  if (c.families.empty()) c.families = cases::every_family();
  if (c.conventions.empty()) c.conventions = own_conventions;
  if (c.places.empty()) c.places = cases::every_place();
  if (c.planes == Planes::unit && c.places.size() > 1)
    c.places.erase(std::remove(c.places.begin(), c.places.end(), cases::Place::scaled),
                   c.places.end());
  if (!c.statuses) c.statuses = own_statuses;
  if (c.defects.empty())
    c.defects.assign(std::begin(cases::all_defects), std::end(cases::all_defects));
  if (c.properties.empty()) c.properties = cases::Checks{}.properties;
  return c;
}

Expected<Contract> exclude(Contract c, const std::vector<std::string>& names) {
  auto drop = [](auto& list, auto value, const auto& every) {
    if (list.empty()) list.assign(std::begin(every), std::end(every));
    list.erase(std::remove(list.begin(), list.end(), value), list.end());
  };
  bool families_named = false, places_named = false, defects_named = false;
  for (const std::string& name : names) {
    if (auto f = cases::parse_family(name)) {
      drop(c.families, *f, cases::all_families);
      families_named = true;
    } else if (auto p = cases::parse_place(name)) {
      drop(c.places, *p, cases::all_places);
      places_named = true;
    } else if (auto d = cases::parse_defect(name)) {
      drop(c.defects, *d, cases::all_defects);
      defects_named = true;
    } else {
      std::vector<std::string> known = names_in(cases::family_names);
      for (const std::vector<std::string>& more :
           {names_in(cases::place_names), names_in(cases::defect_names)})
        known.insert(known.end(), more.begin(), more.end());
      return Expected<Contract>::failure(
          "exclude: " + protocol::unknown_name(
                            "family, hard place or kind of input without an answer", name, known));
    }
  }
  if (families_named && c.families.empty())
    return Expected<Contract>::failure("exclude leaves no family");
  if (places_named && c.places.empty())
    return Expected<Contract>::failure("exclude leaves no hard place");
  if (defects_named && c.defects.empty())
    return Expected<Contract>::failure(
        "exclude leaves no kind of input without an answer (say \"statuses\": \"answers_only\")");
  return c;
}

namespace {

/// Reads one field of a contract's JSON form into `c` ("exclude" into `excluded`); "" or why not.
std::string read_field(Contract& c, const std::string& key, const JsonValue& value,
                       std::vector<std::string>& excluded) {
  std::string error;
  if (key == "families") {
    read_names(value, "families", "family", cases::parse_family, names_in(cases::family_names),
               c.families, error);
  } else if (key == "conventions") {
    const bool all = value.is(JsonValue::Kind::array) && value.items.size() == 1 &&
                     value.items[0].is(JsonValue::Kind::string) && value.items[0].text == "all";
    if (all)
      c.conventions.assign(std::begin(all_conventions), std::end(all_conventions));
    else
      read_names(value, "conventions", "convention", parse_convention, names_in(convention_names),
                 c.conventions, error);
  } else if (key == "places") {
    read_names(value, "places", "hard place", cases::parse_place, names_in(cases::place_names),
               c.places, error);
  } else if (key == "defects") {
    read_names(value, "defects", "kind of input without an answer", cases::parse_defect,
               names_in(cases::defect_names), c.defects, error);
  } else if (key == "properties") {
    read_names(value, "properties", "property", parse_property, property_names(), c.properties,
               error);
  } else if (key == "planes") {
    if (!value.is(JsonValue::Kind::string) || (value.text != "unit" && value.text != "any"))
      return "\"planes\" is \"unit\" or \"any\"";
    c.planes = value.text == "unit" ? Planes::unit : Planes::any;
  } else if (key == "statuses") {
    if (value.is(JsonValue::Kind::string)) {
      c.statuses = parse_status_contract(value.text);
      if (!c.statuses)
        return "\"statuses\": " +
               protocol::unknown_name("status contract", value.text,
                                      names_in(status_contract_names)) +
               ", or a list of refusal codes";
      c.refusals.clear();
    } else if (read_names(value, "statuses", "refusal status", parse_refusal, refusal_names(),
                          c.refusals, error)) {
      c.statuses = StatusContract::exact;
    }
  } else if (key == "row3_accuracy") {
    if (!value.is(JsonValue::Kind::boolean)) return "\"row3_accuracy\" is true or false";
    c.row3_accuracy = value.text == "true";
  } else if (key == "exclude") {
    if (!value.is(JsonValue::Kind::array)) return "\"exclude\" is a list of names";
    for (const JsonValue& item : value.items) {
      if (!item.is(JsonValue::Kind::string)) return "\"exclude\" holds names";
      excluded.push_back(item.text);
    }
  } else if (key == "preset") {
    // One name, as a string or a list of one (a command line's --preset engine).
    const JsonValue* name = &value;
    if (value.is(JsonValue::Kind::array) && value.items.size() == 1) name = &value.items[0];
    if (!name->is(JsonValue::Kind::string)) return "\"preset\" is the name of one preset";
    const std::optional<Contract> preset = preset_contract(name->text);
    if (!preset)
      return "\"preset\": " + protocol::unknown_name("preset", name->text, preset_names());
    c = *preset;
  } else if (key == "answers_only") {
    return "\"answers_only\": true is said \"statuses\": \"answers_only\" in a contract";
  } else {
    return protocol::unknown_name("field", key, field_names());
  }
  return error;
}

}  // namespace

Contract engine_contract() {
  Contract c;
  c.families.assign(std::begin(cases::engine_families), std::end(cases::engine_families));
  c.planes = Planes::unit;
  c.statuses = StatusContract::answers_only;
  return c;
}

std::optional<Contract> preset_contract(std::string_view name) {
  if (name == "engine") return engine_contract();
  return std::nullopt;
}

std::vector<std::string> preset_names() {
  return {"engine"};
}

Expected<Contract> read_contract(std::string_view text) {
  Expected<JsonValue> tree = protocol::parse_json(text, protocol::JsonLimits{4096, 4});
  if (!tree) return Expected<Contract>::failure(tree.error());
  if (!tree->is(JsonValue::Kind::object))
    return Expected<Contract>::failure(std::string("a contract is a JSON object, not ") +
                                       protocol::kind_name(tree->kind));
  Contract c;
  std::vector<std::string> excluded;
  // The preset first, wherever it stands: the other fields change it.
  for (const bool preset : {true, false}) {
    for (const auto& [key, value] : tree->members) {
      if ((key == "preset") != preset) continue;
      if (std::string error = read_field(c, key, value, excluded); !error.empty())
        return Expected<Contract>::failure(error);
    }
  }
  return exclude(std::move(c), excluded);
}

Expected<Contract> with_field(Contract c, const std::string& field,
                              const std::vector<std::string>& names) {
  if (field == "statuses" && names.size() == 1 && !parse_status_contract(names.front()) &&
      !parse_refusal(names.front())) {
    std::vector<std::string> known = names_in(status_contract_names);
    for (const std::string& r : refusal_names()) known.push_back(r);
    return Expected<Contract>::failure(
        "statuses: " + protocol::unknown_name("status contract or refusal", names.front(), known));
  }
  // The JSON value the flag stands for: a string for planes and a status contract's name, a
  // list otherwise (read_field() replaces the field's list with it).
  JsonValue value;
  const bool one_word =
      names.size() == 1 &&
      (field == "planes" || (field == "statuses" && parse_status_contract(names.front())));
  if (one_word) {
    value.kind = JsonValue::Kind::string;
    value.text = names.front();
  } else {
    value.kind = JsonValue::Kind::array;
    for (const std::string& name : names) {
      JsonValue item;
      item.kind = JsonValue::Kind::string;
      item.text = name;
      value.items.push_back(std::move(item));
    }
  }
  std::vector<std::string> excluded;
  if (std::string error = read_field(c, field, value, excluded); !error.empty())
    return Expected<Contract>::failure(error);
  return exclude(std::move(c), excluded);
}

Expected<Contract> read_contract_file(const std::string& path) {
  const Expected<std::string> text = protocol::read_text_file(path, kMaxContractBytes);
  if (!text) return Expected<Contract>::failure("the contract file " + path + ": " + text.error());
  Expected<Contract> c = read_contract(*text);
  if (!c) return Expected<Contract>::failure(path + ": " + c.error());
  return c;
}

std::string contract_json(const Contract& c) {
  std::string out;
  auto field = [&](const char* name, const std::string& value) {
    out += std::string(out.empty() ? "{" : ", ") + "\"" + name + "\": " + value;
  };
  if (!c.families.empty()) field("families", json_names(c.families, cases::family_name));
  if (!c.conventions.empty()) field("conventions", json_names(c.conventions, convention_name));
  if (!c.places.empty()) field("places", json_names(c.places, cases::place_name));
  if (c.planes == Planes::unit) field("planes", "\"unit\"");
  if (c.statuses) {
    if (*c.statuses == StatusContract::exact && !c.refusals.empty())
      field("statuses", json_names(c.refusals, status_code));
    else
      field("statuses", protocol::json_string(status_contract_name(*c.statuses)));
  }
  if (!c.defects.empty()) field("defects", json_names(c.defects, cases::defect_name));
  if (!c.properties.empty()) field("properties", json_names(c.properties, cases::property_name));
  if (c.row3_accuracy) field("row3_accuracy", *c.row3_accuracy ? "true" : "false");
  return out.empty() ? "{}" : out + "}";
}

}  // namespace oblique
