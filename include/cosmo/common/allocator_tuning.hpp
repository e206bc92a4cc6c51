#pragma once
// Process-wide allocator settings for programs that stream LiDAR scans. Every scan allocates and frees buffers of
// megabytes (the bag record, the decoded cloud, scan lines, features, the local map's tree); with glibc's
// defaults such blocks are mapped from and returned to the kernel again and again (mmap / munmap / brk, page
// faults on fresh pages: about half of the system time of an odometry run). Keeping them in the process costs a
// few MB of resident memory. A no-op on other C libraries; results never depend on it.
namespace cosmo {

/// Raises glibc's mmap threshold to 64 MB and its trim threshold to 256 MB (call once, early in main()).
void keepScanBuffersInProcess();

}  // namespace cosmo
