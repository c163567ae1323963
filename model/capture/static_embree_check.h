// Before a capture runs the application: a program that defines Embree's
// functions itself (a statically linked Embree, or stand-ins of its own) calls
// them directly, past any preloaded library, so the shim would see nothing.
// Such a program is refused before it runs, with the reason. The check reads
// the ELF symbol tables of the file the command names (looked up on PATH as
// execvp does); a script, a program that loads Embree as a shared library,
// a stripped static program (no symbol table names rtcIntersect1) and a file
// that cannot be read pass, and the run itself decides (a trace, or the
// merge's "no process loaded a shared libembree3").
#pragma once
#include <string>
#include <vector>

namespace vbsim::capture {

/// The reason `command` cannot be captured because its executable defines
/// rtcIntersect1 itself; empty when the check finds no such definition.
std::string embree_defined_by_program(const std::vector<std::string>& command);

/// The file execvp would run for `name`: `name` itself when it holds a '/',
/// else the first executable file of that name on $PATH; empty when none.
std::string resolve_on_path(const std::string& name);

/// Whether the ELF file at `path` (64-bit, little-endian) defines the function
/// `symbol` in its symbol table or its dynamic symbol table; false for any
/// other file or one that cannot be read.
bool elf_defines_function(const std::string& path, const std::string& symbol);

}  // namespace vbsim::capture
