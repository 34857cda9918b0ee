// The `oblique` executable's subcommands, one file each (apply_command.cpp, verify_command.cpp,
// check_command.cpp, fuzz_report_command.cpp, report_commands.cpp): each sets up its options and
// what it runs once parsed (CLI11's callbacks), storing its exit status in `exit_code`; and the
// options they share (common_options.cpp).
#pragma once

#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "oblique/cases/contract.h"
#include "oblique/oracle/consumers.h"
#include "oblique/protocol/numbers.h"
#include "oblique/shader/shader_function.h"

namespace oblique::cli {

void setup_apply(CLI::App& app, int& exit_code);
/// `argv` gives verify's own arguments, for the replay commands in its reports.
void setup_verify(CLI::App& app, int& exit_code, int argc, char** argv);
void setup_check(CLI::App& app, int& exit_code);
void setup_fuzz_report(CLI::App& app, int& exit_code, const char* self);
void setup_report(CLI::App& app, int& exit_code);

/// Prints the files a report wrote, one per line: exit status 0; 2 when it could not write them
/// (the reason is on standard error already).
int print_paths(const std::optional<std::vector<std::filesystem::path>>& paths);

/// Splits "a,b,c" (spaces ignored).
std::vector<std::string> split_list(const std::string& list);

/// A check that the value is one of `names` (a name table's), saying otherwise which is closest:
/// `unknown convention "opengl" (known: gl, zero_one, reversed_z)`. Its description in the help
/// lists the names.
CLI::Validator one_of(const std::vector<std::string>& names, const std::string& what);

/// --precision: the protocol's scalar names (float, double, long_double), the same option for
/// apply, verify and check; `allowed` are those the subcommand computes or judges in.
CLI::Option* add_precision_option(CLI::App* app, std::string& precision, const std::string& what,
                                  std::vector<protocol::Precision> allowed);

/// --uv-v (verify and check, with --shader): which way the shader's texture coordinate v runs.
CLI::Option* add_uv_v_option(CLI::App* app, std::optional<shader::VDirection>& v);

/// --vectors (verify and check, with --shader): how the shader's matrices multiply vectors.
CLI::Option* add_vectors_option(CLI::App* app, shader::Vectors& vectors);

/// --sampling (verify and check): where depth functions are asked, pixels or arbitrary.
CLI::Option* add_sampling_option(CLI::App* app, oracle::Sampling& sampling);

/// A contract given on the command line (verify, report accuracy): --contract FILE and flags that
/// each set one of its JSON fields from a comma list (--families perspective,infinite).
struct ContractFlags {
  std::string file;  ///< --contract
  struct Field {
    std::string name, flag, list;  ///< the JSON field's name, the flag, its list
  };
  std::vector<Field> fields;
  /// The file's contract (or an empty one) with `first` fields set, then the preset, then each
  /// flag in the order given; an error names the flag, not the JSON field.
  Expected<Contract> read(const std::vector<Field>& first = {}) const;
};

/// Adds `flag` to `app`, setting `field` of `flags`' contract (appended in the order given).
void add_contract_flag(CLI::App* app, const std::shared_ptr<ContractFlags>& flags,
                       const std::string& flag, const std::string& field, const std::string& what);

}  // namespace oblique::cli
