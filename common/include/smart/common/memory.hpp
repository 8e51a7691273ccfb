// Contract: this process's peak resident memory and CPU time, for benchmarks and run summaries.
#pragma once

namespace smart::common {

// VmHWM of /proc/self/status in MB (1 MB = 2^20 bytes): the high-water mark of this process's
// own address space. Not getrusage's ru_maxrss, which after posix_spawn (vfork + exec) also
// counts the parent's memory at the time of the spawn. 0 where /proc is not available.
double peak_rss_mb();

// User + system CPU seconds (getrusage): of this process, or of its waited-for children.
double cpu_seconds_self();
double cpu_seconds_children();
// CPU seconds of the calling thread (CLOCK_THREAD_CPUTIME_ID): work done on a helper thread, to
// tell it apart from the process's (e.g. a recording beside the monitor).
double thread_cpu_seconds();

}  // namespace smart::common
