#pragma once
/// \file ProcessMemory.h
/// The process's resident memory, as the kernel counts it (Linux /proc), for memory estimates
/// (the baseline a run starts from) and their check against the peak (`gale bench memory`).

namespace gale::app {

/// Resident bytes of this process now (/proc/self/statm: resident pages x page size); 0 when
/// /proc cannot be read. Never throws.
double residentBytes();

/// Peak resident bytes of this process so far (VmHWM in /proc/self/status); 0 when /proc cannot
/// be read. Never throws.
double peakResidentBytes();

}  // namespace gale::app
