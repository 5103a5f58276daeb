// SIGINT and SIGTERM as a request to stop (sim/run/stop_request.h): the first is recorded and the
// process goes on, the second of the same kind ends it as usual. Each case runs in a child
// process, so that this executable's other runs never see a stop. What a run does with the
// request (the partial run, the frames kept): tests/sim/regress/test_regress.cpp (Stopping.*).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <functional>

#include "sim/run/stop_request.h"

namespace occsim {
namespace {

// Runs `body` in a child process; returns its wait status.
int inChild(const std::function<int()>& body) {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(body());
    int status = 0;
    ::waitpid(child, &status, 0);
    return status;
}

TEST(StopRequest, TheFirstSignalIsRecordedAndTheProcessGoesOn) {
    for (int signal : {SIGINT, SIGTERM}) {
        const int status = inChild([signal] {
            installStopHandlers();
            if (stopSignal() != 0) return 1;
            std::raise(signal);
            return stopSignal() == signal ? 0 : 2;
        });
        ASSERT_TRUE(WIFEXITED(status)) << signalName(signal);
        EXPECT_EQ(WEXITSTATUS(status), 0) << signalName(signal);
    }
}

TEST(StopRequest, TheSecondSignalOfTheSameKindEndsTheProcess) {
    const int status = inChild([] {
        installStopHandlers();
        std::raise(SIGTERM);
        std::raise(SIGTERM);
        return 0;
    });
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(WTERMSIG(status), SIGTERM);
}

TEST(StopRequest, SignalsAreNamedForTheOneLineMessages) {
    EXPECT_STREQ(signalName(SIGINT), "SIGINT");
    EXPECT_STREQ(signalName(SIGTERM), "SIGTERM");
    EXPECT_STREQ(signalName(SIGSEGV), "SIGSEGV");
    EXPECT_STREQ(signalName(SIGABRT), "SIGABRT");
    EXPECT_STREQ(signalName(SIGUSR1), "a signal");
}

}  // namespace
}  // namespace occsim
