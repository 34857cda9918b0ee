// The AddressSanitizer settings every fuzz target of the project starts with (ASAN_OPTIONS, and
// the [asan] section of a target's .options file under ClusterFuzzLite, still override them).
//
// malloc_context_size=2: ASan records the call stack of every allocation in a store that never
// shrinks. GMP's allocations come from code built without frame pointers, so beyond the second
// frame those stacks are garbage that differs from call to call: measured on fuzz_consumers, the
// store grew to 7.9 million distinct stacks (377 MB after 51k runs, 37-42% of the time spent
// adding to it) and the rate halved within 5 minutes. With two frames it stays at about 2,000.
// A heap error's report still names the allocating function and its caller.
//
// quarantine_size_mb=16: freed memory waits in a quarantine (256 MB by default) before reuse, so
// that a use after free is caught. The checker frees millions of short-lived GMP numbers; once
// the default quarantine is full (after about eight minutes of fuzz_oblique) every allocation
// reuses cache-cold memory: the allocator's share of the time rose from 9% to 16%, the rate fell
// to 83% of its first minute and the process held 640 MB. With 16 MB the steady state comes in
// the first seconds: 100-115% of the first minute over 13 minutes, 139 MB (docs/fuzzing.md).
// A use after free is still caught within the last 16 MB freed.
extern "C" const char* __asan_default_options() {
  return "malloc_context_size=2:quarantine_size_mb=16";
}
