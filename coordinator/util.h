// util.h - kept only for frame_record.cpp, which includes it for strf and moves out of this
// folder with the record format. Every other file includes the header of the job it needs
// (text.h, files.h, clock.h, child_process.h, ...).
#pragma once

#include "text.h"
