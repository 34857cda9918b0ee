// The options the subcommands share: name lists, values checked against the name tables,
// --precision, the printing of a report's files.
#include <algorithm>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "oblique/protocol/names.h"

namespace oblique::cli {

int print_paths(const std::optional<std::vector<std::filesystem::path>>& paths) {
  if (!paths) return 2;
  for (const auto& path : *paths) std::cout << path.string() << "\n";
  return 0;
}

std::vector<std::string> split_list(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream stream(list);
  for (std::string item; std::getline(stream, item, ',');) {
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

CLI::Validator one_of(const std::vector<std::string>& names, const std::string& what) {
  return CLI::Validator(
      [names, what](std::string& value) {
        if (std::find(names.begin(), names.end(), value) != names.end()) return std::string();
        return oblique::protocol::unknown_name(what, value, names);
      },
      "{" + oblique::protocol::name_list(names) + "}");
}

CLI::Option* add_precision_option(CLI::App* app, std::string& precision, const std::string& what,
                                  std::vector<oblique::protocol::Precision> allowed) {
  std::vector<std::string> names;
  for (const oblique::protocol::Precision p : allowed)
    names.emplace_back(oblique::protocol::precision_name(p));
  return app->add_option("--precision", precision, what)
      ->check(one_of(names, "precision"))
      ->capture_default_str();
}

CLI::Option* add_uv_v_option(CLI::App* app, std::optional<shader::VDirection>& v) {
  return app
      ->add_option_function<std::string>(
          "--uv-v", [&v](const std::string& name) { v = shader::parse_v_direction(name); },
          "With --shader: which way the texture coordinate v (and the rows of frag_coord and "
          "texel) runs: up, v = (NDC y + 1) / 2 (GL; Vulkan, whose NDC y points down the image), "
          "or down, v = (1 - NDC y) / 2 (Direct3D, Metal). Default: up for GLSL, down for HLSL")
      ->check(CLI::IsMember({"up", "down"}));
}

CLI::Option* add_vectors_option(CLI::App* app, shader::Vectors& vectors) {
  return app
      ->add_option_function<std::string>(
          "--vectors",
          [&vectors](const std::string& name) { vectors = *shader::parse_vectors(name); },
          "With --shader: how the engine's matrices multiply vectors: column (M v: GLSL M * v, "
          "HLSL mul(M, v); the default) or row (v M: HLSL mul(v, M), DirectXMath style); a "
          "row-vector shader is handed M^T, as its engine's uniforms hold it")
      ->check(CLI::IsMember({"column", "row"}));
}

CLI::Option* add_sampling_option(CLI::App* app, oracle::Sampling& sampling) {
  return app
      ->add_option_function<std::string>(
          "--sampling",
          [&sampling](const std::string& name) { sampling = *oracle::parse_sampling(name); },
          "Where depth functions (view_position, linear_depth) are asked: pixels, the centres "
          "of render targets of real sizes (what a GPU evaluates; the default), or arbitrary, any "
          "NDC position (a stiff mode; a shader that reads a texel is still asked at pixels)")
      ->check(CLI::IsMember({"pixels", "arbitrary"}));
}

Expected<Contract> ContractFlags::read(const std::vector<Field>& first) const {
  Expected<Contract> contract = Contract{};
  if (!file.empty()) contract = read_contract_file(file);
  std::vector<Field> all = first;
  all.insert(all.end(), fields.begin(), fields.end());
  // A preset first: the other flags change it.
  std::stable_partition(all.begin(), all.end(),
                        [](const Field& field) { return field.name == "preset"; });
  for (const Field& field : all) {
    if (!contract) break;
    contract = with_field(std::move(*contract), field.name, split_list(field.list));
    if (!contract) {  // say it in the flag's words, not the JSON field's
      std::string error = contract.error();
      for (const std::string& json_name : {"\"" + field.name + "\"", field.name}) {
        if (error.rfind(json_name + ": ", 0) == 0) {
          error = field.flag + error.substr(json_name.size());
          break;
        }
      }
      return Expected<Contract>::failure(error);
    }
  }
  return contract;
}

void add_contract_flag(CLI::App* app, const std::shared_ptr<ContractFlags>& flags,
                       const std::string& flag, const std::string& field, const std::string& what) {
  app->add_option_function<std::string>(
      flag,
      [flags, field, flag](const std::string& list) {
        flags->fields.push_back({field, flag, list});
      },
      what);
}

}  // namespace oblique::cli
