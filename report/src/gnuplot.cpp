// gnuplot as a child process: posix_spawnp (exec failures come back as an error code rather
// than from a half-started child), output into a log file, status from waitpid.
#include "hylo/report/gnuplot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

extern char** environ;

namespace hylo::report {
namespace {

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The last non-empty line of gnuplot's output: where it says what went wrong.
std::string LastLine(const std::string& text) {
  std::istringstream in(text);
  std::string line, last;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r^") != std::string::npos) last = line;
  }
  return last;
}

std::string Stem(const std::string& png_path) {
  const std::string ext = ".png";
  if (png_path.size() > ext.size() &&
      png_path.compare(png_path.size() - ext.size(), ext.size(), ext) == 0) {
    return png_path.substr(0, png_path.size() - ext.size());
  }
  return png_path;
}

std::string TerminalLine(const std::string& terminal, const GnuplotOptions& o) {
  std::ostringstream s;
  // noenhanced: back-end names such as sliding_window keep their underscores.
  s << "set terminal " << terminal << " size " << o.width_px << "," << o.height_px
    << " noenhanced font \"," << o.font_size_pt << "\"\n";
  return s.str();
}

// One attempt with one terminal.
GnuplotResult RenderWith(const std::string& terminal, const std::string& png_path,
                         const std::string& body, const GnuplotOptions& options) {
  GnuplotResult result;
  result.terminal = terminal;
  result.script = Stem(png_path) + ".gp";
  const std::string log_path = Stem(png_path) + ".log";
  const std::filesystem::path png(png_path);
  const std::string script_name = std::filesystem::path(result.script).filename().string();
  {
    std::ofstream script(result.script);
    script << "# drawn by hylo (hylo::report); redraw with `gnuplot " << script_name
           << "` in this folder\n"
           << TerminalLine(terminal, options) << "set output "
           << GnuplotQuote(png.filename().string()) << "\n"
           << body << "\nunset output\n";
    if (!script) {
      result.message = "cannot write the gnuplot script '" + result.script + "'";
      return result;
    }
  }
  std::remove(png_path.c_str());
  std::string error;
  const int status =
      RunProgram(options.executable, script_name, png.parent_path().string(), log_path, &error);
  result.log = ReadText(log_path);
  result.started = status >= 0;
  if (status < 0) {
    result.message = error;
  } else if (status != 0) {
    result.message = options.executable + " (" + terminal + ") exited with status " +
                     std::to_string(status) + ": " + LastLine(result.log) + " (script " +
                     result.script + ")";
  } else if (!IsPngFile(png_path)) {
    result.message = options.executable + " (" + terminal + ") wrote no PNG image to " + png_path +
                     " (script " + result.script + ")";
  } else {
    result.ok = true;
  }
  return result;
}

}  // namespace

bool GnuplotOptions::IsValid(std::string* why) const {
  std::string reason;
  if (executable.empty()) {
    reason = "executable = '': must name a program";
  } else if (width_px < 100) {
    reason = "width_px = " + std::to_string(width_px) + ": must be >= 100";
  } else if (height_px < 100) {
    reason = "height_px = " + std::to_string(height_px) + ": must be >= 100";
  } else if (font_size_pt < 4) {
    reason = "font_size_pt = " + std::to_string(font_size_pt) + ": must be >= 4";
  }
  if (why != nullptr) *why = reason;
  return reason.empty();
}

int RunProgram(const std::string& executable, const std::string& script_path,
               const std::string& working_dir, const std::string& log_path, std::string* error) {
  // The log is opened before the change of folder: a relative log_path means the caller's.
  const std::string log_absolute = std::filesystem::absolute(log_path).string();
  // A relative program path (./gnuplot) also means the caller's folder.
  const std::string program = executable.find('/') == std::string::npos
                                  ? executable
                                  : std::filesystem::absolute(executable).string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!working_dir.empty()) posix_spawn_file_actions_addchdir_np(&actions, working_dir.c_str());
  posix_spawn_file_actions_addopen(&actions, 1, log_absolute.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<char*> argv{const_cast<char*>(program.c_str()),
                          const_cast<char*>(script_path.c_str()), nullptr};
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    *error = "cannot run '" + executable + "': " + std::strerror(rc) +
             (rc == ENOENT ? " (install gnuplot: apt-get install gnuplot-nox)" : "");
    return -1;
  }
  int wstatus = 0;
  if (waitpid(pid, &wstatus, 0) < 0) {
    *error = "waiting for '" + executable + "' failed: " + std::strerror(errno);
    return -1;
  }
  if (WIFSIGNALED(wstatus)) {
    *error = "'" + executable + "' was killed by signal " + std::to_string(WTERMSIG(wstatus));
    return -1;
  }
  return WEXITSTATUS(wstatus);
}

GnuplotResult RenderPng(const std::string& png_path, const std::string& body,
                        const GnuplotOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) {
    GnuplotResult invalid;
    invalid.message = "GnuplotOptions." + why;
    return invalid;
  }
  GnuplotResult cairo = RenderWith("pngcairo", png_path, body, options);
  if (cairo.ok || !cairo.started) return cairo;  // a missing program will not run as `png`
  GnuplotResult gd = RenderWith("png", png_path, body, options);
  if (!gd.ok) gd.message = "pngcairo: " + cairo.message + "; png: " + gd.message;
  return gd;
}

bool IsPngFile(const std::string& path) {
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::ifstream in(path, std::ios::binary);
  char head[9] = {};
  in.read(head, 9);
  return in.gcount() == 9 && std::memcmp(head, kSignature, 8) == 0;
}

std::string GnuplotQuote(const std::string& text) {
  std::string out = "'";
  for (const char c : text) {
    out += c;
    if (c == '\'') out += '\'';
  }
  return out + "'";
}

}  // namespace hylo::report
