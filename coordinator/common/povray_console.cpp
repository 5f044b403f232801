// povray_console.cpp - reading POV-Ray's console (see povray_console.h).
#include "povray_console.h"

#include "text.h"

namespace fc {

const char *const kProbeMarker = "fc-master probe: options read";
const char *const kProbeShellout = "/bin/true";

namespace {

bool is_noise(const std::string &line)
{
    return line.find("cannot open the user configuration file") != std::string::npos ||
           starts_with(line, "Rendered ") || starts_with(line, "----") ||
           starts_with(line, "====") || line.find(kProbeMarker) != std::string::npos ||
           line.find(kProbeShellout) != std::string::npos;
}

} // namespace

const char *const kShelloutOptions[6] = {"Pre_Scene_Command", "Pre_Frame_Command",
                                         "Post_Frame_Command", "Post_Scene_Command",
                                         "User_Abort_Command", "Fatal_Error_Command"};

std::string failure_excerpt(const std::vector<std::string> &tail)
{
    std::string excerpt = error_excerpt(tail);
    if (excerpt.empty())
        for (size_t k = tail.size() > 8 ? tail.size() - 8 : 0; k < tail.size(); k++)
            if (!is_noise(tail[k]))
                excerpt += tail[k] + "\n";
    return excerpt;
}

bool is_scene_error(const std::vector<std::string> &tail)
{
    for (const std::string &l : tail)
        if (l.find("Parse Error") != std::string::npos ||
            l.find("Fatal error in parser") != std::string::npos ||
            l.find("Fatal error in renderer") != std::string::npos)
            return true;
    return false;
}

std::string error_excerpt(const std::vector<std::string> &tail)
{
    size_t first = tail.size();
    for (size_t i = 0; i < tail.size(); i++) {
        const std::string &l = tail[i];
        if (is_noise(l))
            continue;
        if (l.find("Error") != std::string::npos || l.find("error") != std::string::npos ||
            l.find("Failed") != std::string::npos || l.find("Problem with") != std::string::npos ||
            l.find("fc: cannot") != std::string::npos) {
            first = i;
            break;
        }
    }
    std::string out;
    for (size_t i = first; i < tail.size(); i++) {
        if (is_noise(tail[i]))
            continue;
        out += tail[i] + "\n";
    }
    return out;
}

} // namespace fc
