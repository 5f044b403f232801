// povray_console.h - what POV-Ray's console says when something goes wrong, and the options
// that keep a renderer quiet about it. Read by fc-slave to explain a failed frame and by
// fc-master to explain a rejected scene; only errors, never progress lines, reach the user.
#pragma once

#include <string>
#include <vector>

namespace fc {

// The #error text of fc-master's probe include and the harmless shell-out it sets: the
// lines that carry them are the probe's own, never the scene's.
extern const char *const kProbeMarker;
extern const char *const kProbeShellout;

// POV-Ray's shell-out options. Slaves' renderers get each of them set empty: the master runs
// the commands, once per scene and once per assembled frame.
extern const char *const kShelloutOptions[6];

// From the tail of a failed run, the lines that explain it (from the first error line on),
// without POV-Ray's noise (config-file warnings, statistics).
std::string error_excerpt(const std::vector<std::string> &tail);

// error_excerpt, or when no line says "error", the last lines that are not noise.
std::string failure_excerpt(const std::vector<std::string> &tail);

// Whether a failed run's output says the scene is at fault (a parse error, #error, a fatal
// error of the parser or renderer), as opposed to the host (a crash, a missing program).
bool is_scene_error(const std::vector<std::string> &tail);

} // namespace fc
