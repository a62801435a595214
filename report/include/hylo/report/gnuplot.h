#pragma once
// Runs gnuplot (Debian gnuplot-nox) on a script to draw a PNG. gnuplot is a separate program:
// when it is missing or fails, the caller gets a result saying why (and the report says which
// plot is missing), never an exception or an exit.
// Terminals: pngcairo (antialiased) first, then the libgd `png` terminal when this gnuplot
// build has no cairo.

#include <string>

namespace hylo::report {

struct GnuplotOptions {
  std::string executable = "gnuplot";  ///< program to run (a bare name is looked up on PATH)
  int width_px = 1200;                 ///< image width, pixels, >= 100
  int height_px = 900;                 ///< image height, pixels, >= 100
  int font_size_pt = 11;               ///< text size, points, >= 4

  /// False (with field, value and constraint in *why) when a field is out of range.
  bool IsValid(std::string* why) const;
};

/// What a gnuplot run gave.
struct GnuplotResult {
  bool ok = false;       ///< the PNG exists, is not empty and starts with the PNG signature
  bool started = false;  ///< the program ran (false: missing, not executable, bad options)
  std::string message;   ///< why not ok (one line), or empty
  std::string terminal;  ///< the terminal that drew it ("pngcairo" / "png")
  std::string script;    ///< the script file that was run last
  std::string log;       ///< gnuplot's stdout + stderr of the last run
};

/// Runs `executable script_path` in `working_dir` (empty = the current one) with stdout and
/// stderr written to `log_path`; returns the exit status, or -1 with `*error` set when the
/// program could not be started.
int RunProgram(const std::string& executable, const std::string& script_path,
               const std::string& working_dir, const std::string& log_path, std::string* error);

/// Draws `png_path` with a script made of the terminal settings, `set output`, then `body`
/// (plot commands). Writes the script beside the image (`<png without .png>.gp`) and the log
/// (`.log`), and runs gnuplot in the image's folder: `body` names its data files relative to
/// it, so the folder can be moved and redrawn with `gnuplot <name>.gp`. Tries pngcairo, then
/// png.
GnuplotResult RenderPng(const std::string& png_path, const std::string& body,
                        const GnuplotOptions& options = {});

/// True when the first bytes of `path` are the PNG signature and the file is longer than it.
bool IsPngFile(const std::string& path);

/// `text` as a single-quoted gnuplot string (quotes doubled inside).
std::string GnuplotQuote(const std::string& text);

}  // namespace hylo::report
