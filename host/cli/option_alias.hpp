// SPDX-License-Identifier: Apache-2.0
// Old spellings of renamed options (host/cli/README.md, "Renamed options"): each still parses
// and means exactly the new option, but --help and the shell completion show only the new name.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace palpctl {

/// Adds `old_name` to option's command as a hidden alias of `option` and returns `option`:
/// `--old V` hands V to the option itself, so its checks, defaults and requirements apply and an
/// error names the new spelling; giving both spellings is a usage error. The alias sits in the
/// hidden group (empty group name), which --help and `palpctl completion` leave out.
CLI::Option* add_hidden_alias(CLI::App& cmd, CLI::Option* option, const std::string& old_name);

/// Whether an option is only an old spelling (a hidden alias or any other hidden option).
bool is_hidden(const CLI::Option& option);

}  // namespace palpctl
