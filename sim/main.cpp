// occsim: the simulator executable. Commands: run, bench, regress, merge, history, info, devices,
// cullers, view, why, masked-replay, each in sim/commands/ with its flags; this file reads the
// command line, runs the command given and turns what it ends in into an exit code
// (sim/commands/exit_codes.h). Bad input (flags, scenario and script files, plugins, a headless
// backend or device that is missing or falls short: an occsim::InputError, whichever module found
// it) ends with one line on stderr and exit code 2, and so does `view` where no window can be
// opened; runtime failures (OpenGL, output) with exit 1.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

#include "occsim/culling/contract/input_error.h"
#include "sim/commands/exit_codes.h"
#include "sim/commands/history.h"
#include "sim/commands/listings.h"
#include "sim/commands/masked_replay.h"
#include "sim/commands/merge.h"
#include "sim/commands/regress.h"
#include "sim/commands/run_bench.h"
#include "sim/commands/view.h"
#include "sim/commands/why.h"
#include "sim/output/run_folder.h"
#include "sim/output/shell_quote.h"
#include "sim/output/version.h"
#include "sim/scenario/json_reader.h"

namespace {

using namespace occsim_cli;

// As typed, quoted for a shell, so that summary.json's command pastes back.
std::string commandLine(int argc, char** argv) { return occsim::shellCommand({argv, argv + argc}); }

// Every command's flags, filled by CLI11, and the command each belongs to (set when it is added).
struct Commands {
    CLI::App* run = nullptr;
    RunFlags run_flags;
    CLI::App* bench = nullptr;
    BenchFlags bench_flags;
    CLI::App* regress = nullptr;
    RegressFlags regress_flags;
    CLI::App* merge = nullptr;
    MergeFlags merge_flags;
    CLI::App* history = nullptr;
    HistoryFlags history_flags;
    CLI::App* cullers = nullptr;
    CullersFlags cullers_flags;
    CLI::App* devices = nullptr;
    CLI::App* info = nullptr;
    std::string info_scenario;
    CLI::App* view = nullptr;
    ViewFlags view_flags;
    CLI::App* why = nullptr;
    WhyFlags why_flags;
    CLI::App* masked_replay = nullptr;
    MaskedReplayFlags masked_replay_flags;
};

// The commands in the order --help lists them.
void addCommands(CLI::App& app, Commands& c) {
    c.run = addRun(app, c.run_flags);
    c.bench = addBench(app, c.bench_flags);
    c.regress = addRegress(app, c.regress_flags);
    c.merge = addMerge(app, c.merge_flags);
    c.history = addHistory(app, c.history_flags);
    c.cullers = addCullers(app, c.cullers_flags);
    c.devices = addDevices(app);
    c.info = addInfo(app, c.info_scenario);
    c.view = addView(app, c.view_flags);
    c.why = addWhy(app, c.why_flags);
    c.masked_replay = addMaskedReplay(app, c.masked_replay_flags);
}

// Which flags were given (CLI11 knows once it has parsed): an empty one given is refused.
void noteGivenFlags(Commands& c) {
    c.run_flags.common.out_given = c.run->count("--out") > 0;
    c.bench_flags.common.out_given = c.bench->count("--out") > 0;
    c.bench_flags.algorithms_given = c.bench->count("--algos") > 0;
    c.regress_flags.junit_given = c.regress->count("--junit") > 0;
}

// "The following argument was not expected: --frame" gets the nearest flag of the program.
std::string withSuggestion(const CLI::App& app, const std::string& message) {
    const std::string marker = "not expected: ";
    const size_t at = message.find(marker);
    if (at == std::string::npos) return message;
    std::istringstream rest(message.substr(at + marker.size()));
    std::string word;
    while (rest >> word && word.rfind("--", 0) != 0) {
    }
    if (word.rfind("--", 0) != 0) return message;
    std::vector<std::string> flags;
    for (const CLI::App* sub : app.get_subcommands({})) {
        for (const CLI::Option* option : sub->get_options()) {
            for (const std::string& name : option->get_lnames()) {
                // A flag of another command spelt the same (why's --frame for run's --frames)
                // is no suggestion.
                if ("--" + name != word) flags.push_back("--" + name);
            }
        }
    }
    if (const auto match = occsim::closestMatch(word, flags))
        return message + "; did you mean '" + *match + "'?";
    return message;
}

// CLI11 would answer an unknown command with "A subcommand is required": false, the line
// printed, when argv[1] names none.
bool knownCommand(CLI::App& app, int argc, char** argv) {
    if (argc <= 1 || argv[1][0] == '-') return true;
    std::string commands;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) {
        commands += (commands.empty() ? "" : ", ") + sub->get_name();
        known |= sub->get_name() == argv[1];
    }
    if (!known) {
        std::fprintf(stderr,
                     "occsim: unknown command '%s'; expected one of: %s (see occsim --help)\n",
                     argv[1], commands.c_str());
    }
    return known;
}

// The command that was given, run.
int runGivenCommand(const Commands& c, const std::string& command) {
    if (*c.run) return runCommand(c.run_flags, command);
    if (*c.bench) return benchCommand(c.bench_flags, command);
    if (*c.regress) return regressCommand(c.regress_flags);
    if (*c.merge) return mergeCommand(c.merge_flags);
    if (*c.history) return historyCommand(c.history_flags);
    if (*c.cullers) return cullersCommand(c.cullers_flags);
    if (*c.devices) return devicesCommand();
    if (*c.info) return infoCommand(c.info_scenario);
    if (*c.view) return viewCommand(c.view_flags);
    if (*c.why) return whyCommand(c.why_flags);
    if (*c.masked_replay) return maskedReplayCommand(c.masked_replay_flags);
    return kExitFailure;
}

// An error of several problems (a regression run's plan) is one line per problem, each as the
// command's other errors are.
void printLines(const std::string& message) {
    size_t start = 0;
    while (start <= message.size()) {
        const size_t end = std::min(message.find('\n', start), message.size());
        std::fprintf(stderr, "occsim: %s\n", message.substr(start, end - start).c_str());
        start = end + 1;
    }
}

// dispatch(), with every error a command can end in turned into its one line and exit code:
// bad input (whichever module found it) 2, a failure while running 1. Every command's output
// folder is --out's: a folder that cannot be used is bad input named by that flag, one that
// another run holds (try again later) a failure.
int dispatchReportingErrors(const Commands& c, const std::string& command) {
    try {
        try {
            return runGivenCommand(c, command);
        } catch (const occsim::RunFolderError& e) {  // not an occsim run, or not writable
            throw occsim::givenBy("--out", e);
        } catch (const occsim::RunFolderBusy& e) {
            throw std::runtime_error(std::string("--out ") + e.what());
        }
    } catch (const occsim::InputError& e) {
        printLines(e.what());
        return kExitBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "occsim: %s\n", e.what());
        return kExitFailure;
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "occsim: simulate dynamic scenes and measure occlusion culling against ground truth"};
    app.require_subcommand(1);
    app.set_help_all_flag("--help-all", "Help for every command");
    app.set_version_flag("--version", occsim::versionLine("occsim"),
                         "Print the version and the commit it was built from, and exit");
    Commands c;
    addCommands(app, c);

    if (!knownCommand(app, argc, argv)) return kExitBadInput;
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "occsim: %s (see occsim --help)\n",
                     withSuggestion(app, e.what()).c_str());
        return kExitBadInput;
    }
    noteGivenFlags(c);
    return dispatchReportingErrors(c, commandLine(argc, argv));
}
