#pragma once
// What makes calibrate's figures less than they seem (noise, other load, a hypervisor, a cache
// below the file system): notes for the user, made once everything is measured.

#include "calibrate/calibrate.hpp"

namespace pagecache::calibrate {

/// Appends them to c.notes, from its figures, its system and what the machine did meanwhile.
void add_notes(Calibration& c);

}  // namespace pagecache::calibrate
