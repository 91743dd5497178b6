#pragma once

#include <mpi.h>

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <set>
#include <string>
#include <vector>

namespace glide
{
  /**
   * The directory `<Output/Directory>/<Scene name>/` of one run, and the
   * only code that creates, replaces or removes files in it (P4.1, P5.1).
   *
   * Ownership. glide lists every file it writes there in the manifest
   * `.glide-output` before it creates the file. At the start of a run it
   * removes only the files of that list (and their `.tmp` names) and then
   * refuses to replace any file that exists and is not on the list: a file
   * of the user's is never deleted or overwritten. An existing directory
   * without a manifest is taken over only if it is empty.
   *
   * Complete files only. Every file is written under `<name>.tmp`, checked
   * (stream state; `.vtu`/`.pvd` end with `</VTKFile>`; CSV rows all have
   * the header's columns) and only then renamed. Other writers (contact
   * output) write a step's files into a staging directory; commit_step()
   * checks them, moves the data files into place, and then publishes the
   * indexes (the `.pvd` files and statistics.csv) one right after the other
   * with SIGTERM/SIGINT/SIGHUP blocked. An index is only ever written after
   * the data it lists, so after any fault every file under its final name
   * is complete and every index lists only steps whose files exist. A
   * SIGKILL can leave `.tmp` files and the staging directory, which no
   * index references; the next run in the same directory removes them.
   *
   * Errors are OutputError (exit status 4), raised on every process.
   */
  class OutputDirectory
  {
  public:
    /// `<parent>/<name>`; nothing happens on disk yet.
    OutputDirectory(const std::string &parent,
                    const std::string &name,
                    MPI_Comm           comm);

    /// Removes the staging directory and any `.tmp` file this run left
    /// (after a failure); never throws.
    ~OutputDirectory();

    /**
     * Collective: create the directory (or take it over, see the class
     * documentation), remove the files an earlier run listed in its
     * manifest, start a new manifest and the staging directory.
     */
    void
    prepare();

    /// The directory's path.
    const std::string &
    path() const
    {
      return directory;
    }

    /// Where other writers put a step's files before commit_step().
    const std::string &
    staging() const
    {
      return staging_directory;
    }

    /**
     * Process 0 only: list @p file in the manifest before it is created.
     * Throws OutputError if a file of that name exists that this glide
     * did not write.
     */
    void
    claim(const std::string &file);

    /**
     * Process 0 only: write @p file atomically (claim, write
     * `<file>.tmp` with @p writer, check, rename). Throws OutputError.
     */
    void
    write_file(const std::string                         &file,
               const std::function<void(std::ostream &)> &writer);

    /**
     * Process 0 only: check `<file>.tmp` (see is_complete()) and rename
     * it to @p file; on failure remove it and throw OutputError.
     */
    void
    publish(const std::string &file);

    /**
     * Process 0 only, from the @p write_indexes of commit_step(): write the
     * index @p file under its temporary name and check it; commit_step()
     * renames all indexes together once all are written.
     */
    void
    write_index(const std::string                         &file,
                const std::function<void(std::ostream &)> &writer);

    /**
     * Collective: end an output step. The files in the staging directory
     * are checked and moved into place, data files first; then, with the
     * stop signals blocked, @p write_indexes runs on process 0 (it writes
     * the main `.pvd` and statistics.csv with write_index()); only when all
     * are written and checked are they and the staged `.pvd` files renamed,
     * one right after the other, with the stop signals blocked. On a
     * failure nothing of the step is published.
     */
    void
    commit_step(const std::function<void()> &write_indexes);

    /**
     * Whether @p path holds a complete file of its kind: `.vtu` and `.pvd`
     * end with `</VTKFile>`, `.csv` has a header and every line the same
     * number of columns and ends with a newline; other files are not
     * empty. @p message says what is wrong otherwise.
     */
    static bool
    is_complete(const std::string &path,
                const std::string &kind,
                std::string       &message);

    /// The manifest's file name.
    static const char *const manifest_name;
    /// The staging directory's name.
    static const char *const staging_name;
    /// The lock file's name: a run holds an advisory lock on it from
    /// prepare() to its end, and a second run into the same directory is
    /// refused meanwhile. It stays in the directory.
    static const char *const lock_name;

  private:
    /// Remove the staging directory and this run's `.tmp` files.
    void
    remove_temporaries();

    void
    write_manifest();
    /// Lock the directory @p dir for this run (lock_name); throws
    /// OutputError if another run holds it.
    void
    lock(const std::filesystem::path &dir);
    /// Claim @p file, write `<file>.tmp` with @p writer and check it;
    /// on failure remove it and throw OutputError.
    void
    write_tmp(const std::string                         &file,
              const std::function<void(std::ostream &)> &writer);
    /// Rename @p from to @p file in the directory.
    void
    rename_into_place(const std::string &from, const std::string &file);

    const std::string        directory, staging_directory;
    MPI_Comm                 comm;
    const bool               root;
    std::set<std::string>    manifest;
    std::vector<std::string> pending_indexes;
    /// The lock file's descriptor while this run holds it, else -1.
    int lock_fd = -1;
    /// Whether this run holds the directory (lock()): only then does it
    /// remove temporary files.
    bool owner = false;
  };
} // namespace glide
