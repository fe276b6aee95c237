// Helpers for tests that run the vct program as a separate process: run it with arguments, capture its exit
// status, stdout and stderr separately, and kill it after a hard timeout so a hang fails instead of blocking.
// Header-only (tests/CMakeLists.txt builds only *_test.cpp files).
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace vct::test {

struct RunResult {
    int exitCode = -1;       // the exit status when the process exited normally, else -1
    int signal = 0;          // the signal that ended it (SIGKILL after a timeout), else 0
    bool timedOut = false;   // killed because it ran past the timeout
    std::string startError;  // non-empty when the process could not be started at all
    std::string out, err;    // everything it wrote to stdout and stderr
    double seconds = 0.0;    // wall-clock time

    // Ended by itself with exit(), not by a signal, a timeout or a failure to start.
    bool exited() const { return startError.empty() && !timedOut && signal == 0 && exitCode >= 0; }

    // For failure messages: how it ended, and what it wrote (clipped).
    std::string describe() const {
        auto clip = [](const std::string& text) {
            return text.size() <= 4000 ? text
                                       : text.substr(0, 2000) + "\n[...]\n" + text.substr(text.size() - 2000);
        };
        std::ostringstream s;
        if (!startError.empty())
            s << "could not start: " << startError;
        else if (timedOut)
            s << "timed out after " << seconds << " s (killed)";
        else if (signal)
            s << "killed by signal " << signal << " (" << strsignal(signal) << ")";
        else
            s << "exit code " << exitCode;
        s << " after " << seconds << " s\n--- stdout ---\n" << clip(out) << "\n--- stderr ---\n" << clip(err);
        return s.str();
    }
};

// Runs `program args...` with stdin from /dev/null. The child gets its own process group, so everything it
// started is killed with it on timeout. XDG_RUNTIME_DIR is set to /tmp when unset (lavapipe warns otherwise).
inline RunResult runProcess(const std::string& program, const std::vector<std::string>& args,
                            std::chrono::seconds timeout = std::chrono::seconds(300)) {
    RunResult result;
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };

    if (access(program.c_str(), X_OK) != 0) {
        result.startError = program + ": " + std::strerror(errno);
        return result;
    }
    int outPipe[2], errPipe[2];
    if (pipe2(outPipe, O_CLOEXEC) != 0) {
        result.startError = std::string("pipe: ") + std::strerror(errno);
        return result;
    }
    if (pipe2(errPipe, O_CLOEXEC) != 0) {
        result.startError = std::string("pipe: ") + std::strerror(errno);
        close(outPipe[0]);
        close(outPipe[1]);
        return result;
    }
    // Everything the child needs is prepared before fork: it only calls async-signal-safe functions.
    std::vector<std::string> argvStrings;
    argvStrings.push_back(program);
    argvStrings.insert(argvStrings.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argvStrings) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<char*> envp;
    for (char** e = environ; *e; ++e) envp.push_back(*e);
    static char runtimeDir[] = "XDG_RUNTIME_DIR=/tmp";
    if (std::getenv("XDG_RUNTIME_DIR") == nullptr) envp.push_back(runtimeDir);
    envp.push_back(nullptr);

    const pid_t pid = fork();
    if (pid < 0) {
        result.startError = std::string("fork: ") + std::strerror(errno);
        for (int fd : {outPipe[0], outPipe[1], errPipe[0], errPipe[1]}) close(fd);
        return result;
    }
    if (pid == 0) {
        setpgid(0, 0);
        int devNull = open("/dev/null", O_RDONLY);
        if (devNull >= 0) dup2(devNull, STDIN_FILENO);
        dup2(outPipe[1], STDOUT_FILENO);  // dup2 clears O_CLOEXEC on the new descriptor
        dup2(errPipe[1], STDERR_FILENO);
        execve(program.c_str(), argv.data(), envp.data());
        const char message[] = "test_util: execve failed\n";
        ssize_t ignored = write(STDERR_FILENO, message, sizeof(message) - 1);
        (void)ignored;
        _exit(127);
    }
    setpgid(pid, pid);  // also from here, so the group exists whichever side runs first
    close(outPipe[1]);
    close(errPipe[1]);

    // Read both pipes until they close and the child has exited. Once it has exited, whatever still holds
    // the pipes (a process it left behind) gets a short grace period, then the pipes are abandoned.
    const auto deadline = start + timeout;
    auto drainDeadline = deadline;
    pollfd fds[2] = {{outPipe[0], POLLIN, 0}, {errPipe[0], POLLIN, 0}};
    std::string* sinks[2] = {&result.out, &result.err};
    int openCount = 2;
    bool reaped = false;
    int status = 0;
    while (openCount > 0 || !reaped) {
        if (!reaped) {
            pid_t r = waitpid(pid, &status, WNOHANG);
            if (r == pid) {
                reaped = true;
                drainDeadline =
                    std::min(deadline, std::chrono::steady_clock::now() + std::chrono::milliseconds(500));
            } else if (r < 0 && errno != EINTR) {
                result.startError = std::string("waitpid: ") + std::strerror(errno);
                break;
            }
        }
        const auto now = std::chrono::steady_clock::now();
        if (!reaped && now >= deadline) {
            result.timedOut = true;
            kill(-pid, SIGKILL);
            kill(pid, SIGKILL);
            while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            reaped = true;
            break;
        }
        if (reaped && (openCount == 0 || now >= drainDeadline)) break;
        if (openCount == 0) {  // pipes closed but the child still runs: poll its exit
            usleep(2000);
            continue;
        }
        // Short slices while the child runs, so its exit is noticed even if something else holds the pipes.
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>((reaped ? drainDeadline : deadline) - now);
        int ready = poll(fds, 2, int(std::clamp<long long>(left.count(), 1, 50)));
        if (ready < 0 && errno != EINTR) break;
        if (ready <= 0) continue;
        for (int i = 0; i < 2; ++i) {
            if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            char buffer[65536];
            ssize_t n = read(fds[i].fd, buffer, sizeof(buffer));
            if (n > 0) {
                sinks[i]->append(buffer, size_t(n));
            } else if (n == 0 || errno != EINTR) {
                close(fds[i].fd);
                fds[i].fd = -1;
                --openCount;
            }
        }
    }
    for (pollfd& p : fds)
        if (p.fd >= 0) close(p.fd);
    kill(-pid, SIGKILL);  // anything it left running in its process group (usually nothing: ESRCH)

    if (reaped && WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
    if (reaped && WIFSIGNALED(status)) result.signal = WTERMSIG(status);
    result.seconds = elapsed();
    return result;
}

// The vct program under test (VCT_BINARY from tests/CMakeLists.txt).
inline RunResult runVct(const std::vector<std::string>& args,
                        std::chrono::seconds timeout = std::chrono::seconds(300)) {
    return runProcess(VCT_BINARY, args, timeout);
}

// A sample model of the shared scenes (VCT_SHARED_SCENES: ../shared/scenes), NAME/glTF/NAME.gltf. The project runs
// without them: a test that needs one begins with VCT_REQUIRE_SHARED(NAME) and is skipped where it is absent.
inline std::filesystem::path sharedModel(const std::string& name) {
    return std::filesystem::path(VCT_SHARED_SCENES) / name / "glTF" / (name + ".gltf");
}

// A fresh directory under VCT_TEST_OUTPUT (emptied first).
inline std::filesystem::path freshOutputDir(const std::string& relative) {
    std::filesystem::path dir = std::filesystem::path(VCT_TEST_OUTPUT) / relative;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

inline std::string readTextFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void writeTextFile(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

inline void writeBinaryFile(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// Rec. 709 luminance of linear RGB.
inline float luminance(float r, float g, float b) {
    return 0.2126f * r + 0.7152f * g + 0.0722f * b;
}

// Number of NaN or infinite values among `values`.
inline size_t countNonFinite(const std::vector<float>& values) {
    size_t n = 0;
    for (float v : values) n += std::isfinite(v) ? 0 : 1;
    return n;
}

// How two equally sized lists of values (two images' channels) differ: how many differ at all, and the largest
// relative difference among them (to say how far apart a failed exact comparison is).
struct ExactDifference {
    size_t different = 0;
    double largestRelative = 0.0;
};
inline ExactDifference exactDifference(const std::vector<float>& a, const std::vector<float>& b) {
    ExactDifference d;
    for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        d.different += a[i] != b[i];
        const double scale = std::max(std::abs(double(a[i])), std::abs(double(b[i])));
        if (scale > 0.0)
            d.largestRelative = std::max(d.largestRelative, std::abs(double(a[i]) - b[i]) / scale);
    }
    return d;
}

}  // namespace vct::test

// Skips the test where the shared sample model NAME is absent (test::sharedModel).
#define VCT_REQUIRE_SHARED(name)                                  \
    if (!std::filesystem::exists(::vct::test::sharedModel(name))) \
    GTEST_SKIP() << "no " << ::vct::test::sharedModel(name) << " (shared scenes not available)"
