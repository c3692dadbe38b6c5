// Soak of `geocean query --points -` over a stream (issue 17 item 3): rows
// are generated on a pipe into the command (no file on disk), its answers
// read back from another pipe and checked row by row, its resident set
// sampled from /proc/<pid>/statm once a second while it runs.
//   soak_query_stream <rows> [geocean executable] [extra query options...]
// Checked: exit 0, the header, then exactly <rows> answer rows, row i
// echoing row i's lat,lon (nothing lost, duplicated or reordered) with the
// 14 fields of the text format; the resident set after the first 10 % of
// the rows never more than 32 MiB above its value there (the pipeline holds
// at most 8 blocks of 1 MiB of input and their answers: growth beyond that
// would be memory kept per row). Prints one line of figures; exit 0 = all
// held, 1 = a check failed, 2 = usage.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

extern char** environ;

namespace {

using Clock = std::chrono::steady_clock;

// Row i's lat,lon as text: four decimals (the shortest round trip of
// m / 1e4 is m / 1e4 itself, so the command echoes exactly this text), the
// points spread over the globe by a multiplicative step.
std::size_t rowText(std::uint64_t i, char* b) {
  const std::uint64_t a = (i * 2654435761u) % 1600001u;   // lat -80 .. 80
  const std::uint64_t c = (i * 40503u + 7u) % 3600001u;   // lon -180 .. 180
  const double lat = -80.0 + double(a) / 1e4, lon = -180.0 + double(c) / 1e4;
  char* p = std::to_chars(b, b + 32, lat).ptr;
  *p++ = ',';
  p = std::to_chars(p, p + 32, lon).ptr;
  return std::size_t(p - b);
}

long residentKiB(pid_t pid) {
  char path[64];
  std::snprintf(path, sizeof path, "/proc/%d/statm", int(pid));
  std::FILE* f = std::fopen(path, "r");
  if (!f) return -1;
  long size = 0, resident = 0;
  const int got = std::fscanf(f, "%ld %ld", &size, &resident);
  std::fclose(f);
  return got == 2 ? resident * (sysconf(_SC_PAGESIZE) / 1024) : -1;
}

bool writeAll(int fd, const char* p, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w;
    n -= std::size_t(w);
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: soak_query_stream <rows> [geocean executable] [query options...]\n");
    return 2;
  }
  const std::uint64_t rows = std::strtoull(argv[1], nullptr, 10);
  const std::string exe = argc > 2 ? argv[2] : GEOCEAN_EXE;
  std::vector<std::string> args = {exe, "query", "--points", "-"};
  for (int i = 3; i < argc; ++i) args.emplace_back(argv[i]);
  std::vector<char*> cargs;
  for (auto& s : args) cargs.push_back(s.data());
  cargs.push_back(nullptr);

  signal(SIGPIPE, SIG_IGN);  // a child that dies mid-stream is reported, not fatal here
  int in[2], out[2];
  if (pipe2(in, O_CLOEXEC) != 0 || pipe2(out, O_CLOEXEC) != 0) {
    std::perror("soak_query_stream: pipe");
    return 1;
  }
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, in[0], 0);
  posix_spawn_file_actions_adddup2(&fa, out[1], 1);
  pid_t pid = 0;
  if (const int e = posix_spawn(&pid, exe.c_str(), &fa, nullptr, cargs.data(), environ); e != 0) {
    std::fprintf(stderr, "soak_query_stream: cannot start %s: %s\n", exe.c_str(), std::strerror(e));
    return 1;
  }
  posix_spawn_file_actions_destroy(&fa);
  close(in[0]);
  close(out[1]);
  const auto t0 = Clock::now();

  // Writer: the rows, in 64 KiB writes.
  std::atomic<bool> writeFailed{false};
  std::thread writer([&] {
    std::vector<char> buf(1 << 16);
    std::size_t used = 0;
    const std::string header = "lat,lon\n";
    std::memcpy(buf.data(), header.data(), header.size());
    used = header.size();
    for (std::uint64_t i = 0; i < rows; ++i) {
      if (used + 80 > buf.size()) {
        if (!writeAll(in[1], buf.data(), used)) {
          writeFailed = true;
          break;
        }
        used = 0;
      }
      used += rowText(i, buf.data() + used);
      buf[used++] = '\n';
    }
    if (!writeFailed && !writeAll(in[1], buf.data(), used)) writeFailed = true;
    close(in[1]);
  });

  // Sampler: the child's resident set once a second, with the row count
  // the reader has reached (so "after 10 % of the rows" has a meaning).
  std::atomic<std::uint64_t> rowsRead{0};
  std::atomic<bool> done{false};
  std::mutex m;
  std::vector<std::pair<std::uint64_t, long>> samples;  // (rows read, KiB)
  std::thread sampler([&] {
    while (!done) {
      const long kib = residentKiB(pid);
      if (kib > 0) {
        std::lock_guard<std::mutex> l(m);
        samples.emplace_back(rowsRead.load(), kib);
      }
      for (int k = 0; k < 10 && !done; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });

  // Reader: header, then row i must start with row i's "lat,lon," and have 14 fields.
  std::uint64_t got = 0, bad = 0, firstBad = 0;
  std::string firstBadLine;
  bool headerSeen = false, headerOk = false;
  {
    std::vector<char> buf(1 << 20);
    std::string partial;
    char expect[80];
    auto line = [&](std::string_view l) {
      if (!headerSeen) {
        headerSeen = true;
        headerOk = l.substr(0, 18) == "lat,lon,surface,el";
        return;
      }
      const std::size_t n = rowText(got, expect);
      expect[n] = ',';
      const bool ok = l.size() > n && std::memcmp(l.data(), expect, n + 1) == 0 &&
                      std::count(l.begin(), l.end(), ',') == 13;
      if (!ok && bad++ == 0) {
        firstBad = got;
        firstBadLine = std::string(l.substr(0, 200));
      }
      ++got;
    };
    for (;;) {
      const ssize_t r = ::read(out[0], buf.data(), buf.size());
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) break;
      std::size_t pos = 0;
      const std::size_t len = std::size_t(r);
      while (pos < len) {
        const void* nl = std::memchr(buf.data() + pos, '\n', len - pos);
        if (!nl) {
          partial.append(buf.data() + pos, len - pos);
          break;
        }
        const std::size_t end = std::size_t(static_cast<const char*>(nl) - buf.data());
        if (partial.empty()) {
          line(std::string_view(buf.data() + pos, end - pos));
        } else {
          partial.append(buf.data() + pos, end - pos);
          line(partial);
          partial.clear();
        }
        pos = end + 1;
      }
      rowsRead = got;
    }
    if (!partial.empty()) ++bad;  // a last line without its newline
  }
  close(out[0]);
  writer.join();
  int status = 0;
  waitpid(pid, &status, 0);
  done = true;
  sampler.join();
  const double wallS = std::chrono::duration<double>(Clock::now() - t0).count();

  // Memory: the sample at 10 % of the rows is the reference.
  long ref = -1, maxAfter = 0, first = samples.empty() ? -1 : samples.front().second, last = first, peak = 0;
  for (const auto& [r, kib] : samples) {
    peak = std::max(peak, kib);
    last = kib;
    if (ref < 0 && r >= rows / 10) ref = kib;
    if (ref >= 0) maxAfter = std::max(maxAfter, kib);
  }
  const long growth = ref < 0 ? 0 : maxAfter - ref;
  const bool exitOk = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  std::printf("soak_query_stream: %llu rows in, %llu answer rows out, %llu bad (first at row %llu), header %s, "
              "exit %s, %.1f s wall; resident set (%zu samples) first %ld KiB, at 10 %% of the rows %ld KiB, "
              "max after %ld KiB (growth %ld KiB), peak %ld KiB, last %ld KiB\n",
              (unsigned long long)rows, (unsigned long long)got, (unsigned long long)bad,
              (unsigned long long)firstBad, headerOk ? "ok" : "wrong",
              WIFEXITED(status) ? std::to_string(WEXITSTATUS(status)).c_str() : "by signal", wallS,
              samples.size(), first, ref, maxAfter, growth, peak, last);
  if (bad) std::fprintf(stderr, "soak_query_stream: first bad answer row: %s\n", firstBadLine.c_str());
#ifdef __SANITIZE_ADDRESS__
  // Under ASan the resident set is the allocator's quarantine and shadow,
  // not the command's heap (as for ViewMemory): rows are checked, not memory.
  const bool memoryOk = true;
#else
  const bool memoryOk = growth <= 32 * 1024;
#endif
  const bool pass = exitOk && !writeFailed && headerOk && bad == 0 && got == rows && memoryOk;
  return pass ? 0 : 1;
}
