// SPDX-License-Identifier: Apache-2.0
// Hidden aliases for renamed options (option_alias.hpp).
#include "option_alias.hpp"

namespace palpctl {

CLI::Option* add_hidden_alias(CLI::App& cmd, CLI::Option* option, const std::string& old_name) {
  const std::string new_name = option->get_name();
  const CLI::callback_t forward = [option, old_name, new_name](const CLI::results_t& values) {
    if (option->count() > 0)
      throw CLI::ValidationError(old_name, "is the old spelling of " + new_name + ": give one of them");
    for (const auto& v : values) option->add_result(v);
    option->run_callback();  // the option's own checks, conversion and callback
    return true;
  };
  // CLI11 processes a command's options in the order they were added, so the alias (added after
  // the option) finds the option not yet given or already processed; requirements and exclusions
  // are checked after all callbacks and so see the forwarded value.
  cmd.add_option(old_name, forward, "old spelling of " + new_name)
      ->type_size(option->get_type_size_min(), option->get_type_size_max())
      ->expected(option->get_expected_min(), option->get_expected_max())
      ->group("");
  return option;
}

bool is_hidden(const CLI::Option& option) { return option.get_group().empty(); }

}  // namespace palpctl
