// The subcommands of `cullcheck`, one file each. add_<name> registers the subcommand and its
// flags on the program and returns what runs it once the command line has been parsed; the
// runner returns the exit code and throws InputError / std::invalid_argument on bad input.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace cullcheck::cli {

using Runner = std::function<int()>;

Runner add_generate(CLI::App& app);
Runner add_cull(CLI::App& app);
Runner add_verify(CLI::App& app);
Runner add_region(CLI::App& app);
Runner add_cell(CLI::App& app);
Runner add_vbaoi(CLI::App& app);
Runner add_report(CLI::App& app);
Runner add_gate(CLI::App& app);
Runner add_fuzz(CLI::App& app);
Runner add_html(CLI::App& app);
Runner add_merge(CLI::App& app);
Runner add_radar(CLI::App& app);

}  // namespace cullcheck::cli
