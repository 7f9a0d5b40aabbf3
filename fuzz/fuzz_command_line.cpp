// Fuzz harness: the command line of a run (apps/cli_app.hpp, the parser exasph itself uses).
// Input: the arguments, one per line. Every combination must either parse into a configuration
// that validate_config accepts, or be refused with CLI11's message or an exasph::Error; the run
// itself is not started.
#include <cstdint>
#include <string>
#include <vector>

#include "../apps/subcommands.hpp"
#include "exasph/config/validate.hpp"
#include "fuzz_support.hpp"

namespace {

std::vector<std::string> arguments(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> args{"exasph"};
    std::string arg;
    for (std::size_t i = 0; i < size; ++i) {
        if (data[i] != '\n') {
            arg += char(data[i]);
            continue;
        }
        args.push_back(arg);
        arg.clear();
    }
    if (!arg.empty()) args.push_back(arg);
    return args;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size > 4096) return 0;
    auto args = arguments(data, size);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    CommandLine cl;
    CLI::App& app = cl.app;
    try {
        app.parse(int(argv.size()), argv.data());
    } catch (const CLI::Error&) { // help, version or a parse error: CLI11's own message
        return 0;
    }
    if (app.got_subcommand("glass") || app.got_subcommand("exact")) return 0;
    exasph::fuzz::expect_clear_refusal([&] {
        exasph::cli::finish_configuration(app, cl.cfg);
        exasph::validate_config(cl.cfg);
    });
    return 0;
}
