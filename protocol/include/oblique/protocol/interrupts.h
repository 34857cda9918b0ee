// What a Ctrl-C (SIGINT, or SIGTERM / SIGHUP) does to a long command: the programs it runs in
// process groups of their own are ended, the command's "interrupted" line is written to standard
// error (what ran, the seed, the command that repeats or continues it), and the process dies of
// the signal as before (exit status 128 + signal).
#pragma once

#include <sys/types.h>
#include <cstddef>
#include <string>

namespace oblique::protocol {

/// Installs the handler for SIGINT, SIGTERM and SIGHUP where the program has not taken them
/// itself (a handler already there, or SIG_IGN for a background job, is left alone). Idempotent.
void handle_interrupts();

/// The line an interrupt writes (a newline is appended), replacing the one before; empty: none.
/// Cheap enough to call after every batch. Not for a signal handler.
void set_interrupt_line(const std::string& line);

/// From now on the first interrupt does not end the program: the programs' groups are ended,
/// the signal is remembered (interrupted()) and the program finishes what it can, then dies of it
/// (die_of_interrupt()); a second interrupt ends it at once. For a command that keeps what it
/// finished (fuzz-report writes the reports of the inputs it ran).
void finish_on_interrupt();
/// The interrupt that came in finish_on_interrupt() mode, 0 if none.
int interrupted();
/// Writes the interrupted line (if any) and dies of `sig` as the interrupt asked.
[[noreturn]] void die_of_interrupt(int sig);

/// What the handler removes before dying, so an interrupt leaves nothing half made: a staging
/// `folder` (the files in it, then itself; never a link) or an empty file holding a reserved name
/// (removed only while it is empty). keep_on_interrupt() takes one back once it is committed or
/// gone. At most kMaxRemovals at once, paths of at most kMaxRemovalPath bytes (others are not
/// remembered: the destructors still remove them on a normal exit).
inline constexpr int kMaxRemovals = 32;
inline constexpr std::size_t kMaxRemovalPath = 4096;
void remove_on_interrupt(const std::string& path, bool folder);
void keep_on_interrupt(const std::string& path);

/// A process group that the handler ends (SIGKILL) before dying; forget it once it is reaped.
void remember_child_group(pid_t group);
void forget_child_group(pid_t group);

}  // namespace oblique::protocol
