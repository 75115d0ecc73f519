#include "rts/test_workers.h"

#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <string>

#include "rts/cli_support.h"
#include "rts/scenario_support.h"

namespace warpath::tools {
namespace {

using Clock = std::chrono::steady_clock;

struct Worker {
  pid_t pid = -1;
  int fd = -1;  // the read end of the pipe the worker writes its result to
  std::size_t index = 0;
  std::string output;
  Clock::time_point began;
};

CaseResult failedToRun(const TestCase& testCase, const std::string& message) {
  CaseResult r = notRun(testCase);
  r.status = CaseStatus::Error;
  r.message = message;
  return r;
}

CaseResult cannotStart(const TestCase& testCase) {
  return failedToRun(testCase,
                     std::string("cannot start a worker process: ") + std::strerror(errno));
}

void writeAll(int fd, const std::string& text) {
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // the parent is gone; nobody to tell
    written += static_cast<std::size_t>(n);
  }
}

// The worker process: runs the case and sends its result as JSON, then leaves without running
// destructors or flushing the stdio buffers it inherited (the parent's to print).
[[noreturn]] void workerMain(const TestCase& testCase, int fd) {
  std::string text;
  try {
    text = caseJson(runCase(testCase), true)
               .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  } catch (...) {
    text.clear();  // the parent reports a worker that sent nothing
  }
  writeAll(fd, text);
  ::_exit(0);
}

// Reads what the worker sent; on end of file reaps it and turns its output into a result.
std::optional<CaseResult> readFrom(Worker& w, const TestCase& testCase) {
  char buffer[65536];
  const ssize_t n = ::read(w.fd, buffer, sizeof buffer);
  if (n > 0) {
    w.output.append(buffer, static_cast<std::size_t>(n));
    return std::nullopt;
  }
  if (n < 0 && (errno == EINTR || errno == EAGAIN)) return std::nullopt;
  ::close(w.fd);
  int status = 0;
  while (::waitpid(w.pid, &status, 0) < 0 && errno == EINTR) {
  }
  CaseResult r;
  if (WIFSIGNALED(status)) {
    r = failedToRun(testCase, "crashed: signal " + std::to_string(WTERMSIG(status)) + " (" +
                                  ::strsignal(WTERMSIG(status)) + ")");
  } else {
    try {
      r = caseFromJson(nlohmann::json::parse(w.output), testCase.file);
    } catch (const nlohmann::json::exception&) {
      r = failedToRun(testCase, "the worker process ended without a result (exit status " +
                                    std::to_string(WEXITSTATUS(status)) + ")");
    } catch (const BadInput& e) {
      r = failedToRun(testCase, e.message);
    }
  }
  r.seconds = std::chrono::duration<double>(Clock::now() - w.began).count();
  return r;
}

}  // namespace

std::size_t runInWorkers(const std::vector<TestCase>& cases, int jobs,
                         const std::function<void(std::size_t, CaseResult)>& done) {
  std::vector<Worker> running;
  std::size_t next = 0;
  bool forwarded = false;
  for (;;) {
    while (!interruptRequested() && next < cases.size() &&
           running.size() < static_cast<std::size_t>(jobs)) {
      const std::size_t index = next++;
      int fds[2];
      if (::pipe(fds) != 0) {
        done(index, cannotStart(cases[index]));
        continue;
      }
      std::fflush(stdout);  // what is printed so far, once
      std::fflush(stderr);
      const pid_t pid = ::fork();
      if (pid == 0) {
        ::close(fds[0]);
        for (const Worker& w : running)
          ::close(w.fd);
        workerMain(cases[index], fds[1]);
      }
      ::close(fds[1]);
      if (pid < 0) {
        ::close(fds[0]);
        done(index, cannotStart(cases[index]));
        continue;
      }
      running.push_back({pid, fds[0], index, {}, Clock::now()});
    }
    if (running.empty()) break;
    // A signal sent to this process alone (kill PID, Slurm's SIGTERM at a time limit) reaches
    // the workers too; from a terminal they have it already, and twice does no harm.
    if (interruptRequested() && !forwarded) {
      for (const Worker& w : running)
        ::kill(w.pid, SIGINT);
      forwarded = true;
    }
    std::vector<pollfd> polled;
    for (const Worker& w : running)
      polled.push_back({w.fd, POLLIN, 0});
    if (::poll(polled.data(), polled.size(), 200) < 0) continue;  // EINTR: look again
    for (std::size_t i = running.size(); i-- > 0;) {
      if (polled[i].revents == 0) continue;
      Worker& w = running[i];
      if (std::optional<CaseResult> r = readFrom(w, cases[w.index])) {
        const std::size_t index = w.index;
        running.erase(running.begin() + static_cast<std::ptrdiff_t>(i));
        done(index, std::move(*r));
      }
    }
  }
  return next;
}

}  // namespace warpath::tools
