// fc_master_main.cpp - fc-master's entry point: the process-wide settings that must come
// before any thread starts, then the render (master.h).
#include <unistd.h>

#include <cstdlib>

#include "command_line.h"
#include "debug_log.h"
#include "freed_memory.h"
#include "image_codec.h"
#include "image_writer_client.h"
#include "master.h"
#include "watchdog.h"

using namespace fc;

int main(int argc, char **argv)
{
    keep_freed_memory();
    Options opt = parse_options(argc, argv);
    // OpenBLAS, loaded with OpenImageIO, would start a spinning thread per core for nothing.
    setenv("OPENBLAS_NUM_THREADS", "1", 0);
    // The virtual machine sets PVM_TMP (and, as root, PVM_ALLOW_ROOT) later, while OpenImageIO
    // may be loading in another thread, where its libraries' constructors call getenv: adding
    // a variable reallocates the environment under them (a crash, seen in the tests). Present
    // from the start, they are only replaced in place. Set as PVM reads them when unset.
    setenv("PVM_TMP", "/tmp", 0);
    if (geteuid() == 0)
        setenv("PVM_ALLOW_ROOT", "1", 0);
    watchdog::start("fc-master");
    Master master(opt);
    int rc = master.run();
    debug_log("run done");
    wait_image_io();
    stop_image_writer();
    debug_log("frames written");
    return rc;
}
