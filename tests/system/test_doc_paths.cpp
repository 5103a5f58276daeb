// Every repository path the docs, the READMEs and the code comments name exists, and every link
// between pages lands on a heading that exists: a file moved or renamed leaves no page or comment
// pointing at where it used to be (tests/support/repo_paths.h says what counts as a path).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "repo_paths.h"
#include "shell_command.h"

namespace occsim::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = OCCSIM_SOURCE_DIR;

std::string readText(const fs::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::string> trackedFiles() {
    const Outcome listed = shell("git -C '" + kRoot.string() + "' ls-files");
    EXPECT_EQ(listed.exit_code, 0) << listed.output;
    std::vector<std::string> files;
    std::istringstream lines(listed.output);
    for (std::string line; std::getline(lines, line);) files.push_back(line);
    return files;
}

// The repository's top-level folders: the first word of every path that names one.
std::set<std::string> topFolders(const std::vector<std::string>& files) {
    std::set<std::string> folders;
    for (const std::string& f : files) {
        if (const size_t slash = f.find('/'); slash != std::string::npos) {
            folders.insert(f.substr(0, slash));
        }
    }
    return folders;
}

bool endsWith(const std::string& s, std::string_view suffix) {
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

enum class Kind { Markdown, CppComments, HashComments, None };

Kind kindOf(const std::string& file) {
    if (endsWith(file, ".md")) return Kind::Markdown;
    if (endsWith(file, ".h") || endsWith(file, ".cpp") || endsWith(file, ".h.in")) {
        return Kind::CppComments;
    }
    if (endsWith(file, "CMakeLists.txt") || endsWith(file, ".cmake") || endsWith(file, ".sh") ||
        endsWith(file, ".py") || endsWith(file, ".cmake.in") || file == ".ci/run") {
        return Kind::HashComments;
    }
    return Kind::None;
}

// A named path exists: as a file or folder, or as the template a configure step makes it from
// (sim/output/build_info.h from build_info.h.in).
bool exists(const fs::path& root, const std::string& path) {
    return fs::exists(root / path) || fs::exists(root / (path + ".in"));
}

// "file:line: path" for each path `text` (the contents of `file`) names that does not exist under
// `root`, and "file:line: page#anchor" for each link to a heading that does not exist.
std::vector<std::string> missingPaths(const fs::path& root, const std::string& file,
                                      const std::string& text,
                                      const std::set<std::string>& top_folders) {
    std::vector<NamedPath> named;
    const Kind kind = kindOf(file);
    if (kind == Kind::Markdown) {
        named = repositoryWords(text, top_folders);
        const auto links = markdownLinks(text, fs::path(file).parent_path());
        named.insert(named.end(), links.begin(), links.end());
    } else if (kind != Kind::None) {
        named = repositoryWords(commentsOnly(text, kind == Kind::HashComments), top_folders);
    }
    std::vector<std::string> missing;
    for (const NamedPath& p : named) {
        const std::string where = file + ":" + std::to_string(p.line) + ": ";
        const std::string page = p.path.empty() ? file : p.path;  // "#anchor": this page
        if (!p.path.empty() && !exists(root, page)) {
            missing.push_back(where + p.path);
        } else if (!p.anchor.empty() && endsWith(page, ".md")) {
            const std::string target = page == file ? text : readText(root / page);
            if (!headingAnchors(target).count(p.anchor)) {
                missing.push_back(where + page + "#" + p.anchor);
            }
        }
    }
    return missing;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string all;
    for (const std::string& l : lines) all += l + "\n";
    return all;
}

TEST(DocPaths, EveryPathInTheDocsReadmesAndCodeCommentsExists) {
    const std::vector<std::string> files = trackedFiles();
    ASSERT_FALSE(files.empty());
    const std::set<std::string> tops = topFolders(files);
    std::vector<std::string> missing;
    size_t scanned = 0;
    for (const std::string& file : files) {
        if (kindOf(file) == Kind::None) continue;
        ++scanned;
        const auto m = missingPaths(kRoot, file, readText(kRoot / file), tops);
        missing.insert(missing.end(), m.begin(), m.end());
    }
    EXPECT_GT(scanned, 100u);
    EXPECT_TRUE(missing.empty()) << "paths that name no file of the repository (moved? renamed? "
                                    "update the page or comment):\n"
                                 << joined(missing);
}

// The check can fail: planted stale paths, in a page and in comments, are each found (a header's
// path from before it moved, a private header named by a public include path), and what is no path
// (placeholders, string literals, web links, paths inside other paths) is not.
TEST(DocPaths, PlantedStalePathsAreFoundAndPlaceholdersAreNot) {
    const std::set<std::string> tops = topFolders(trackedFiles());
    const std::string page =
        "# Title\n"
        "The contract is `culling/algorithms.h`, see [the tree](bsp-tree.md) and\n"
        "[gone](no-such-page.md), [a heading](cli.md#no-such-heading), [here](#title),\n"
        "[there](#nowhere), `culling/tree/{bsp_tree.cpp,tree_builder.h}`, "
        "`culling/tree/bsp_tree.{cpp,x}`.\n"
        "Placeholders: `scenarios/small/X.json`, `occsim/culling/<room>/<file>.h`, `docs/*.md`,\n"
        "`culling/cullers/my_culler.cpp`, `./build/release/sim/occsim`, https://x.org/docs/a.md,\n"
        "`occsim/culling/contract/culler.h`, `occsim/culling/culler.h`, "
        "`sim/output/build_info.h`.\n"
        "Moved: `culling/contract/culler.h`; private, not public: `culling/tree/tree_builder.h`, "
        "`occsim/culling/tree/tree_builder.h`.\n";
    EXPECT_EQ(joined(missingPaths(kRoot, "docs/planted.md", page, tops)),
              "docs/planted.md:2: culling/algorithms.h\n"
              "docs/planted.md:4: culling/tree/bsp_tree.x\n"
              "docs/planted.md:7: culling/include/occsim/culling/culler.h\n"
              "docs/planted.md:8: culling/contract/culler.h\n"
              "docs/planted.md:8: culling/include/occsim/culling/tree/tree_builder.h\n"
              "docs/planted.md:3: docs/no-such-page.md\n"
              "docs/planted.md:3: docs/cli.md#no-such-heading\n"
              "docs/planted.md:4: docs/planted.md#nowhere\n");

    const std::string cpp =
        "// Implements culling/culler.h.\n"
        "const char* kFile = \"scenarios/bad-input.json\";  // sim/no_such.h\n"
        "auto s = R\"(// docs/not-a-comment.md)\";\n"
        "/* render/gone.h\n"
        "   render/gl_api.h */ int x = 1'000;  // tune/none.h\n";
    EXPECT_EQ(joined(missingPaths(kRoot, "sim/planted.cpp", cpp, tops)),
              "sim/planted.cpp:1: culling/culler.h\n"
              "sim/planted.cpp:2: sim/no_such.h\n"
              "sim/planted.cpp:4: render/gone.h\n"
              "sim/planted.cpp:5: tune/none.h\n");

    const std::string cmake = "set(X \"docs/string.md\")  # see docs/gone.md\n# scripts/test.sh\n";
    EXPECT_EQ(joined(missingPaths(kRoot, "tests/CMakeLists.txt", cmake, tops)),
              "tests/CMakeLists.txt:1: docs/gone.md\n");
}

}  // namespace
}  // namespace occsim::testing
