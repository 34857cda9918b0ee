// What each engine idiom claims, read from idioms.txt (the one list: CTest, the campaign script,
// the property test and the fuzz target read it): its convention and families, as the engine
// contract narrowed to them (unit planes, answers only), and its implementation in its storage.
#pragma once

#include <oblique/cases/contract.h>
#include <oblique/oracle/adapter.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine_matrices.h"

namespace engine_matrices {

struct Claims {
  std::string name;
  oblique::Contract contract;
  oblique::Layout layout = oblique::Layout::column_major;
  std::string names_twin;  ///< what names the wrong twin (a regular expression)
};

/// Every line of `path` (idioms.txt): name | storage | convention | families | names the twin.
/// Throws std::runtime_error on a line it cannot read.
inline std::vector<Claims> read_claims(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::vector<Claims> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::stringstream s(line);
    for (std::string field; std::getline(s, field, '|');) fields.push_back(field);
    if (fields.size() != 5) throw std::runtime_error(path + ": not five fields: " + line);
    Claims c;
    c.name = fields[0];
    const Idiom* idiom = find(c.name, nullptr);
    if (!idiom) throw std::runtime_error(path + ": no idiom " + c.name);
    const Storage storage = idiom->storage;
    if (fields[1] != (storage == Storage::row_vectors ? "row_vectors" : "column_major"))
      throw std::runtime_error(path + ": " + c.name + " is not stored " + fields[1]);
    c.layout = storage == Storage::row_vectors ? oblique::Layout::row_vectors
                                               : oblique::Layout::column_major;
    c.contract = oblique::engine_contract();
    const auto convention = oblique::parse_convention(fields[2]);
    if (!convention) throw std::runtime_error(path + ": no convention " + fields[2]);
    c.contract.conventions = {*convention};
    c.contract.families.clear();
    std::stringstream families(fields[3]);
    for (std::string name; std::getline(families, name, ',');) {
      const auto family = oblique::cases::parse_family(name);
      if (!family) throw std::runtime_error(path + ": no family " + name);
      c.contract.families.push_back(*family);
    }
    c.names_twin = fields[4];
    out.push_back(c);
  }
  return out;
}

/// The idiom of `claims` (its twin with `wrong`) as an implementation, in its own storage.
inline oblique::oracle::Implementation<float> implementation(const Claims& claims, bool wrong) {
  const Idiom* idiom = find(claims.name, nullptr);
  return oblique::adapt<float>(claims.name + (wrong ? "_wrong" : ""), claims.layout,
                               claims.contract.conventions.front(),
                               wrong ? idiom->wrong : idiom->right);
}

}  // namespace engine_matrices
