// The docs' command blocks as the tests run them. A fenced block right under a marker
// "<!-- runnable -->" or "<!-- runnable: OPTION, OPTION... -->" is a promise that it runs as
// written; the options say how:
//   exit N          it ends with status N (default 0)
//   shell NAME      the shell that runs it (default sh); `bash` for a script that says #!/bin/bash
//   file NAME       a file the next blocks use (a Slurm job script): written to the folder, not run
//   completions N   a YAML block with a Kubernetes container: its `command:` runs once per index
//                   0..N-1 with JOB_COMPLETION_INDEX and the container's `env:`, each pod ending
//                   with status `exit` (what lets the Indexed Job complete)
//   volume PATH     PATH (a volume's mountPath, /results) stands for volume/PATH in the folder
//   id NAME         a name other tests find the block by (tests/cluster/slurm_regress.sh)
// Blocks run with `set -e`, in the order of the doc, in one folder (a block may use what an
// earlier one wrote), the built occsim first on PATH and ./build/release/sim/occsim replaced by
// it, and the stand-ins of tests/doc_stand_ins (sbatch, kubectl) next on PATH.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "shell_command.h"

namespace occsim::testing {

struct DocBlock {
    std::string where;  // file:line of the marker
    int expect = 0;
    std::string shell = "sh";
    std::string file;
    int completions = 0;
    std::string volume;
    std::string id;
    std::string script;
};

// Applies one marker option to the block; false for an option this runner does not know.
inline bool applyMarkerOption(const std::string& option, DocBlock& block) {
    std::istringstream words(option);
    std::string key, value;
    words >> key >> value;
    if (value.empty()) return false;
    if (key == "exit") return std::sscanf(value.c_str(), "%d", &block.expect) == 1;
    if (key == "completions") return std::sscanf(value.c_str(), "%d", &block.completions) == 1;
    if (key == "shell")
        block.shell = value;
    else if (key == "file")
        block.file = value;
    else if (key == "volume")
        block.volume = value;
    else if (key == "id")
        block.id = value;
    else
        return false;
    return true;
}

inline std::vector<DocBlock> runnableBlocks(const std::string& text, const std::string& file) {
    std::vector<DocBlock> blocks;
    std::istringstream in(text);
    std::string line;
    int number = 0;
    const std::string open = "<!-- runnable", close = " -->";
    while (std::getline(in, line)) {
        ++number;
        if (line.rfind(open, 0) != 0 || !line.ends_with(close)) continue;
        DocBlock block;
        block.where = file + ":" + std::to_string(number);
        std::string options = line.substr(open.size(), line.size() - open.size() - close.size());
        if (!options.empty()) {
            if (options[0] != ':') {
                ADD_FAILURE() << block.where << ": expected <!-- runnable: OPTION, ... -->";
                continue;
            }
            std::istringstream list(options.substr(1));
            std::string option;
            while (std::getline(list, option, ',')) {
                if (!applyMarkerOption(option, block))
                    ADD_FAILURE() << block.where << ": unknown runnable option '" << option << "'";
            }
        }
        if (!std::getline(in, line) || line.rfind("```", 0) != 0) {
            ADD_FAILURE() << block.where
                          << ": a runnable marker must stand right above a fenced block";
            continue;
        }
        ++number;
        while (std::getline(in, line) && line.rfind("```", 0) != 0) {
            ++number;
            block.script += line + "\n";
        }
        ++number;
        blocks.push_back(block);
    }
    return blocks;
}

inline std::string readDoc(const std::string& doc) {
    std::ifstream in(std::filesystem::path(OCCSIM_SOURCE_DIR) / doc);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline DocBlock docBlockWithId(const std::string& doc, const std::string& id) {
    for (const DocBlock& block : runnableBlocks(readDoc(doc), doc)) {
        if (block.id == id) return block;
    }
    ADD_FAILURE() << doc << " has no runnable block with id " << id;
    return {};
}

inline void replaceAll(std::string& s, const std::string& from, const std::string& to) {
    for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
        s.replace(at, from.size(), to);
}

inline std::string singleQuoted(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// The double-quoted strings of `text` from `from` on, backslash escapes kept as written, up to
// `end` (npos: the end of the text). Plain scanning, not <regex>: GCC 12 warns falsely
// (-Wmaybe-uninitialized) inside std::regex in the sanitizer build, where warnings are errors.
inline std::vector<std::string> quotedStrings(const std::string& text, size_t from, size_t end) {
    std::vector<std::string> out;
    end = std::min(end, text.size());
    for (size_t i = from; i < end; ++i) {
        if (text[i] != '"') continue;
        std::string value;
        for (++i; i < end && text[i] != '"'; ++i) {
            if (text[i] == '\\' && i + 1 < end) value += text[i++];
            value += text[i];
        }
        out.push_back(value);
    }
    return out;
}

// The container's command of a YAML block: the strings of `command: ["sh", "-c", "..."]`.
inline std::vector<std::string> podCommand(const std::string& yaml) {
    const size_t key = yaml.find("command: [");
    if (key == std::string::npos) return {};
    const size_t line_end = yaml.find('\n', key);
    const size_t close = yaml.rfind(']', line_end == std::string::npos ? yaml.size() : line_end);
    if (close == std::string::npos || close < key) return {};
    return quotedStrings(yaml, key + 10, close);
}

// The container's `env:` entries written as `- {name: NAME, value: "VALUE"}`.
inline std::map<std::string, std::string> podEnvironment(const std::string& yaml) {
    std::map<std::string, std::string> env;
    const std::string name_key = "{name: ", value_key = ", value: ";
    for (size_t at = yaml.find(name_key); at != std::string::npos;
         at = yaml.find(name_key, at + 1)) {
        const size_t name_start = at + name_key.size();
        const size_t comma = yaml.find(value_key, name_start);
        const size_t brace = yaml.find('}', name_start);
        if (comma == std::string::npos || brace == std::string::npos || comma > brace) continue;
        const std::vector<std::string> value = quotedStrings(yaml, comma, brace);
        if (value.size() == 1) env[yaml.substr(name_start, comma - name_start)] = value[0];
    }
    return env;
}

// Writes `script` with the runner's preamble into `dir` and runs it with `shell`.
inline Outcome runScript(const std::string& shell_name, const std::string& script,
                         const std::filesystem::path& dir, const std::string& name = "block.sh") {
    const auto stand_ins = std::filesystem::path(OCCSIM_SOURCE_DIR) / "tests" / "doc_stand_ins";
    const auto file = dir / name;
    std::ofstream(file) << "set -e\nexport PATH='"
                        << std::filesystem::path(OCCSIM_EXE).parent_path().string() << "':'"
                        << stand_ins.string() << "':\"$PATH\"\ncd '" << dir.string() << "'\n"
                        << script;
    return shell(shell_name + " " + file.string());
}

// Runs the block in `dir` as its marker says (see the top of this file).
inline Outcome runBlock(const DocBlock& block, const std::filesystem::path& dir) {
    std::string script = block.script;
    replaceAll(script, "./build/release/sim/occsim", OCCSIM_EXE);
    if (!block.volume.empty()) {
        const std::filesystem::path volume = dir / "volume" / block.volume.substr(1);
        std::filesystem::create_directories(volume);
        replaceAll(script, block.volume + "/", volume.string() + "/");
    }
    if (!block.file.empty()) {
        std::ofstream(dir / block.file) << script;
        return {0, ""};
    }
    if (block.completions > 0) {
        const std::vector<std::string> argv = podCommand(script);
        if (argv.empty()) return {-1, block.where + ": no `command: [...]` in the YAML block"};
        std::string exports;
        for (const auto& [name, value] : podEnvironment(script))
            exports += "export " + name + "=" + singleQuoted(value) + "\n";
        std::string command;
        for (const std::string& word : argv) command += singleQuoted(word) + " ";
        Outcome all{block.expect, ""};
        for (int index = 0; index < block.completions; ++index) {
            const Outcome pod =
                runScript("sh",
                          exports + "export JOB_COMPLETION_INDEX=" + std::to_string(index) + "\n" +
                              "exec " + command + "\n",
                          dir, "pod.sh");
            all.output += "pod " + std::to_string(index) + ": exit " +
                          std::to_string(pod.exit_code) + "\n" + pod.output;
            if (pod.exit_code != block.expect) all.exit_code = pod.exit_code;
        }
        return all;
    }
    return runScript(block.shell, script, dir);
}

}  // namespace occsim::testing
