// What a Ctrl-C (SIGINT, or SIGTERM / SIGHUP) does to a long command: the programs it runs in
// process groups of their own are ended, the command's "interrupted" line is written to standard
// error (what ran, the seed, the command that repeats or continues it), and the process dies of
// the signal as before (exit status 128 + signal).
#pragma once

#include <sys/types.h>
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

/// A process group that the handler ends (SIGKILL) before dying; forget it once it is reaped.
void remember_child_group(pid_t group);
void forget_child_group(pid_t group);

}  // namespace oblique::protocol
