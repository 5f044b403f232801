// render_plan.cpp - the programs, POV-Ray's answers and the tiles (see render_plan.h).
#include "render_plan.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <thread>

#include "files.h"
#include "frame_encoder.h"
#include "host_info.h"
#include "render_blocks.h"
#include "schedule.h"
#include "temp_dirs.h"
#include "text.h"

namespace fc {

namespace {

bool find_programs(const Options &opt, RenderPlan &plan, std::string &err)
{
    std::string here = self_dir();
    if (!opt.povray.empty()) {
        plan.renderer = which(opt.povray);
        if (plan.renderer.empty()) {
            err = "renderer " + opt.povray + " not found or not executable";
            return false;
        }
    } else if (const char *env = getenv("FC_POVRAY"); env && *env) {
        plan.renderer = which(env);
    } else if (is_executable(here + "/povray-fc")) {
        plan.renderer = here + "/povray-fc";
    } else {
        plan.renderer = which("povray-fc");
    }
    if (plan.renderer.empty()) {
        err = "no renderer found (povray-fc); use --povray PATH";
        return false;
    }
    plan.renderer = absolute_path(plan.renderer);

    std::string slave = opt.slave.empty() ? here + "/fc-slave" : opt.slave;
    if (slave.find('/') == std::string::npos)
        slave = which(slave).empty() ? slave : which(slave);
    plan.slave_program = absolute_path(slave);
    if (!is_executable(plan.slave_program)) {
        err = "slave program " + plan.slave_program + " is missing or not executable (build it "
              "with 'make coordinator', or use --slave PATH)";
        return false;
    }
    char buf[PATH_MAX];
    if (!getcwd(buf, sizeof buf))
        return sys_fail(err, "getcwd");
    plan.cwd = buf;
    return true;
}

bool ask_povray(const Options &opt, const std::string &tmpdir, RenderPlan &plan,
                std::string &err)
{
    // Both questions to POV-Ray at once: each start of povray-fc costs a tenth of a second.
    // The user's options alone: the format and names are those one povray-fc process with
    // them writes (its povray.ini included).
    double limit = std::max(30.0, opt.timeout);
    std::string scene_err, ini_err;
    bool ini_ok = false;
    ResolvedOptions ini;
    std::thread resolved([&] {
        ini_ok = probe_resolved_options(plan.renderer, opt.pov, plan.cwd, tmpdir, limit, ini,
                                        ini_err);
    });
    // OpenImageIO loads meanwhile when frames will need it, while the processors are mostly
    // idle. Not before the thread above: while dlopen() runs, glibc's loader lock stalls
    // every pthread_create.
    FrameEncoder::preload_while_probing(opt.division);
    bool scene_ok = probe_scene(plan.renderer, opt.pov, plan.cwd, tmpdir, limit, plan.scene,
                                scene_err);
    resolved.join();
    err = !scene_ok ? scene_err : ini_err;
    if (!scene_ok || !ini_ok)
        return false;
    if (!output_format(ini, plan.format, err) ||
        !frame_size_possible(plan.format, channel_encoding(ini, plan.format), plan.scene.width,
                             plan.scene.height, machine_memory(), err) ||
        !split_output_name(plan.scene, plan.format.ext, err) || !set_frames(plan.scene, ini, err))
        return false;
    plan.resolved = ini;
    return true;
}

} // namespace

bool make_render_plan(const Options &opt, RenderPlan &plan, std::string &err)
{
    if (!find_programs(opt, plan, err))
        return false;
    std::string tmpdir;
    remove_stale_dirs(temp_root(), "fc-master-");
    if (!make_temp_dir(temp_root(), strf("fc-master-%d-", int(getpid())), tmpdir, err))
        return false;
    bool ok = ask_povray(opt, tmpdir, plan, err);
    remove_tree(tmpdir);
    if (!ok)
        return false;
    // The slaves' renderers write the format resolved here, whatever their host's povray.ini
    // says. A renderer with the frame channel (the shell-out probe needs it) has frame
    // coherence: the channel's patches come after fc's.
    plan.format_options = {format_option(plan.format)};
    if (opt.fc)
        plan.extra.push_back(kFrameCoherenceOption);
    if (opt.division != Division::Sequence) {
        // Blocks inside tiles: no block traced by two slaves where the pixels allow it.
        int block = slave_render_block(plan.resolved, opt.tile);
        if (block > 0)
            plan.extra.push_back(strf("Render_Block_Size=%d", block));
    }
    std::string scene = resolved_value(plan.resolved, "Input_File_Name", "");
    plan.scene_path = absolute_path(!scene.empty() && scene[0] == '/' ? scene
                                                                      : plan.cwd + "/" + scene);
    read_shellouts(plan.resolved, plan.shellouts);
    plan.shellouts.permitted = plan.scene.shellouts_permitted;
    plan.shellouts.width = plan.scene.width;
    plan.shellouts.height = plan.scene.height;
    plan.tiles = opt.division == Division::Sequence ? std::vector<Rect>{plan.scene.area}
                                                    : make_tiles(plan.scene.area, opt.tile);
    return true;
}

} // namespace fc
