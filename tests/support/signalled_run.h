// Runs an executable for the end-to-end tests of stopping: its stderr on a pseudo-terminal, so
// that it prints its progress line as it does for a person at a terminal, and a signal sent once
// a chosen text (the first progress line) has appeared there: a Ctrl-C after the first frames.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <string>
#include <vector>

namespace occsim::testing {

struct SignalledRun {
    bool exited = false;  // exited by itself (else ended by a signal, or never started)
    int exit_code = -1;   // when exited
    int ended_by = 0;     // the signal that ended it, when it did not exit
    bool signal_sent = false;
    std::string terminal;  // what it wrote to stderr
};

// `argv[0]` is the executable's path; stdout goes to `stdout_file`. The signal is sent when
// `ready` first appears on stderr (never, when it is empty); a run still going after `give_up` is
// killed (a hang guard, never a measurement).
inline SignalledRun runAndSignal(const std::vector<std::string>& argv, const std::string& ready,
                                 int signal, const std::string& stdout_file,
                                 std::chrono::seconds give_up = std::chrono::seconds(600)) {
    SignalledRun run;
    const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) return run;
    const std::string slave_name = ::ptsname(master);
    const pid_t pid = ::fork();
    if (pid < 0) return run;
    if (pid == 0) {
        const int slave = ::open(slave_name.c_str(), O_RDWR | O_NOCTTY);
        const int out = ::open(stdout_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (slave < 0 || out < 0) ::_exit(127);
        const rlimit no_core{0, 0};  // a test that crashes it on purpose leaves no core file
        ::setrlimit(RLIMIT_CORE, &no_core);
        ::dup2(out, STDOUT_FILENO);
        ::dup2(slave, STDERR_FILENO);
        ::close(master);
        std::vector<char*> args;
        for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        ::execv(args[0], args.data());
        ::_exit(127);
    }
    const auto deadline = std::chrono::steady_clock::now() + give_up;
    char buffer[4096];
    while (true) {
        pollfd p{master, POLLIN, 0};
        const int ready_fds = ::poll(&p, 1, 100);
        if (ready_fds > 0) {
            const ssize_t n = ::read(master, buffer, sizeof buffer);
            if (n <= 0) break;  // the terminal closed: the process ended
            run.terminal.append(buffer, static_cast<size_t>(n));
        }
        if (!run.signal_sent && !ready.empty() && run.terminal.find(ready) != std::string::npos) {
            ::kill(pid, signal);
            run.signal_sent = true;
        }
        if (std::chrono::steady_clock::now() > deadline) ::kill(pid, SIGKILL);
    }
    ::close(master);
    int status = 0;
    ::waitpid(pid, &status, 0);
    run.exited = WIFEXITED(status);
    run.exit_code = run.exited ? WEXITSTATUS(status) : -1;
    run.ended_by = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
    return run;
}

}  // namespace occsim::testing
