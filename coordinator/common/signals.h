// signals.h - the signals fc-master and fc-slave handle themselves.
#pragma once

namespace fc {

// Routes SIGINT, SIGTERM and SIGHUP to `handler` and ignores SIGPIPE (a dead peer's pipe
// must give EPIPE, not kill the process).
void install_signal_handlers(void (*handler)(int));

} // namespace fc
