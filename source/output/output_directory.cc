#include <glide/base/collective_failure.h>
#include <glide/output/interruption.h>
#include <glide/output/output_directory.h>
#include <glide/output/output_error.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

namespace glide
{
  namespace fs = std::filesystem;

  const char *const OutputDirectory::manifest_name = ".glide-output";
  const char *const OutputDirectory::staging_name  = ".glide-staging";
  const char *const OutputDirectory::lock_name     = ".glide-lock";

  void
  throw_output_error_on_any_process(const std::string &failure, MPI_Comm comm)
  {
    throw_first_failure<OutputError>(failure, comm);
  }

  namespace
  {
    bool
    ends_with(const std::string &s, const std::string &suffix)
    {
      return s.size() >= suffix.size() &&
             s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
    }

    /// A disk with no free block left: a write there may have been cut
    /// short even if the writer (contact output) did not check.
    bool
    disk_full(const std::string &path)
    {
      struct statvfs s;
      return statvfs(path.c_str(), &s) == 0 && s.f_blocks > 0 && s.f_bfree == 0;
    }

    std::string
    kind_of(const std::string &file)
    {
      std::string f = file;
      if (ends_with(f, ".tmp"))
        f.resize(f.size() - 4);
      const auto dot = f.rfind('.');
      return dot == std::string::npos ? "" : f.substr(dot);
    }

    std::string
    in_quotes(const fs::path &p)
    {
      return "'" + p.string() + "'";
    }

    /// @p advice (advice()) ended with the advice to check the output
    /// directory's parameter, unless it already names it.
    std::string
    with_check(const std::string &advice)
    {
      return advice + (advice.find("'Output/Directory'") == std::string::npos ?
                         ". Check 'Output/Directory'." :
                         ".");
    }
  } // namespace

  std::string
  advice(const int error)
  {
    std::string text = std::strerror(error);
    if (error == ENOSPC || error == EDQUOT)
      text += "; the disk is full: free space there or choose another "
              "'Output/Directory'";
    else if (error == EFBIG)
      text += "; the file size limit of the process (ulimit -f) was "
              "reached: raise it, or write less (e.g. 'Output/Write VTU = "
              "false')";
    else if (error == EACCES || error == EPERM || error == EROFS)
      text += "; choose an 'Output/Directory' you may write in";
    return text;
  }



  OutputDirectory::OutputDirectory(const std::string &parent,
                                   const std::string &name,
                                   MPI_Comm           comm)
    : directory(parent + "/" + name)
    , staging_directory(parent + "/" + name + "/" + staging_name)
    , comm(comm)
    , root(dealii::Utilities::MPI::this_mpi_process(comm) == 0)
  {
    // A run ended at once by the watchdog (interruption.h) leaves what
    // this destructor would leave.
    if (root)
      set_cleanup_at_once(this, [this] { remove_temporaries(); });
  }



  OutputDirectory::~OutputDirectory()
  {
    if (!root)
      return;
    clear_cleanup_at_once(this);
    remove_temporaries();
    // Closing the lock file releases the lock (the file stays: removing
    // it could let a third run lock a new file while a second one holds
    // the old).
    if (lock_fd >= 0)
      ::close(lock_fd);
  }



  void
  OutputDirectory::remove_temporaries()
  {
    // Only what this run made: a run refused because another one holds
    // the directory must not touch that run's staging directory.
    if (!owner)
      return;
    std::error_code ec;
    fs::remove_all(staging_directory, ec);
    for (const auto &f : manifest)
      fs::remove(fs::path(directory) / (f + ".tmp"), ec);
  }



  void
  OutputDirectory::prepare()
  {
    std::string failure;
    if (root)
      try
        {
          const fs::path  dir(directory);
          std::error_code ec;
          // Open MPI's parallel file writing (MPI-IO with shared file
          // locks) aborts with a buffer overflow on file names of about
          // 256 characters or more; its processes then die after the solve.
          // The longest name written in parallel: <staging>/<scene
          // name>-NNNN.vtu.
          if (dealii::Utilities::MPI::n_mpi_processes(comm) > 1)
            {
              const std::string longest =
                (fs::absolute(fs::path(staging_directory), ec) /
                 (dir.filename().string() + "-0000.vtu"))
                  .string();
              if (longest.size() > 240)
                throw OutputError(
                  "Under MPI the results' file names may be at most 240 "
                  "characters long with their directory; " +
                  in_quotes(fs::path(longest)) + " has " +
                  std::to_string(longest.size()) +
                  ", and Open MPI's parallel file writing aborts on longer "
                  "ones. Choose a shorter 'Output/Directory' or 'Scene "
                  "name'.");
            }
          if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
            throw OutputError("The output directory " + in_quotes(dir) +
                              " exists and is not a directory; choose another "
                              "'Output/Directory' or 'Scene name'.");
          const bool created = fs::create_directories(dir, ec);
          if (ec)
            throw OutputError("Cannot create the output directory " +
                              in_quotes(dir) + ": " +
                              with_check(advice(ec.value())));

          // A directory without a manifest is taken over only if it is
          // empty (but for the lock file of a run that was refused or is
          // starting).
          const fs::path manifest_path = dir / manifest_name;
          if (!fs::exists(manifest_path, ec) && !created)
            {
              std::vector<std::string> entries;
              for (const auto &e : fs::directory_iterator(dir, ec))
                if (e.path().filename() != lock_name)
                  entries.push_back(e.path().filename().string());
              if (ec)
                throw OutputError("Cannot read the output directory " +
                                  in_quotes(dir) + ": " + advice(ec.value()) +
                                  ".");
              if (!entries.empty())
                throw OutputError(
                  "The output directory " + in_quotes(dir) +
                  " already holds files that glide did not write (e.g. '" +
                  entries.front() + "'; glide lists what it writes in '" +
                  manifest_name +
                  "', and there is none), and glide never deletes or "
                  "overwrites a file it did not write. Choose another "
                  "'Scene name' or 'Output/Directory', or move those files "
                  "away (results of a glide older than this one: remove "
                  "the directory).");
            }
          lock(dir);
          // What an earlier run wrote here, read under the lock.
          std::vector<std::string> earlier;
          if (fs::exists(manifest_path, ec))
            {
              std::ifstream in(manifest_path);
              std::string   line;
              while (std::getline(in, line))
                // Plain names only: never follow a path out of here.
                if (!line.empty() && line[0] != '#' &&
                    line.find('/') == std::string::npos && line != "." &&
                    line != "..")
                  earlier.push_back(line);
              earlier.push_back(staging_name);
            }
          for (const auto &f : earlier)
            for (const std::string suffix : {"", ".tmp"})
              {
                const fs::path p = dir / (f + suffix);
                if (f == staging_name && suffix.empty())
                  fs::remove_all(p, ec);
                else
                  fs::remove(p, ec);
                if (ec)
                  throw OutputError("Cannot remove the earlier result " +
                                    in_quotes(p) + ": " + advice(ec.value()) +
                                    ".");
              }
          manifest = {staging_name};
          write_manifest();
          fs::create_directory(staging_directory, ec);
          if (ec)
            throw OutputError("Cannot create " + in_quotes(staging_directory) +
                              ": " + advice(ec.value()) + ".");
        }
      catch (const OutputError &e)
        {
          failure = e.what();
        }
      catch (const std::exception &e)
        {
          failure = "Cannot prepare the output directory '" + directory +
                    "': " + e.what();
        }
    throw_output_error_on_any_process(failure, comm);
    // Every process writes its part of the results in parallel (MPI-IO,
    // collective): each must see the directory the first process made and
    // be able to write there (another file system, another working
    // directory, a full disk on its node), or the others would wait for
    // it in the first collective write.
    if (dealii::Utilities::MPI::n_mpi_processes(comm) > 1)
      {
        const fs::path probe =
          fs::path(staging_directory) /
          (".probe-" +
           std::to_string(dealii::Utilities::MPI::this_mpi_process(comm)));
        {
          std::ofstream out(probe);
          out << "glide\n";
          out.close();
          if (out.fail())
            failure =
              "Process " +
              std::to_string(dealii::Utilities::MPI::this_mpi_process(comm)) +
              " cannot write into the output directory " +
              in_quotes(fs::path(directory)) +
              " that the first process prepared: " +
              advice(errno ? errno : EIO) +
              ". Every process must see the same 'Output/Directory' "
              "(give an absolute path on a file system shared by "
              "all nodes).";
        }
        std::error_code ec;
        fs::remove(probe, ec);
        throw_output_error_on_any_process(failure, comm);
      }
  }



  void
  OutputDirectory::lock(const fs::path &dir)
  {
    // Two runs writing into one directory remove each other's files, and
    // their indexes list the other's data (a second run with the same
    // 'Scene name' took over the directory of a live one, until
    // 2026-12-06). An advisory lock, released by the operating system
    // however the process ends, even by SIGKILL.
    const fs::path path = dir / lock_name;
    lock_fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock_fd < 0)
      throw OutputError("Cannot create " + in_quotes(path) + ": " +
                        with_check(advice(errno)));
    if (::flock(lock_fd, LOCK_EX | LOCK_NB) != 0)
      {
        if (errno != EWOULDBLOCK)
          {
            owner = true; // a file system without locks: go on without
            return;
          }
        std::string holder;
        {
          std::ifstream in(path);
          std::getline(in, holder);
        }
        ::close(lock_fd);
        lock_fd = -1;
        throw OutputError(
          "The output directory " + in_quotes(dir) +
          " is in use by another glide run" +
          (holder.empty() ? std::string() : " (" + holder + ")") +
          ": two runs writing into one directory would remove each "
          "other's results. Wait for it to end, or choose another 'Scene "
          "name' or 'Output/Directory'.");
      }
    owner          = true;
    char host[256] = {};
    ::gethostname(host, sizeof(host) - 1);
    const std::string holder = "process " + std::to_string(::getpid()) +
                               " on " + std::string(host) + "\n";
    if (::ftruncate(lock_fd, 0) == 0)
      {
        const auto written = ::pwrite(lock_fd, holder.data(), holder.size(), 0);
        (void)written; // only informative: the lock is what counts
      }
  }



  void
  OutputDirectory::write_manifest()
  {
    const fs::path dir(directory);
    const fs::path tmp = dir / (std::string(manifest_name) + ".tmp");
    {
      std::ofstream out(tmp);
      out << "# glide's output directory. glide wrote the files listed "
             "below and replaces them\n# at its next run here; it never "
             "touches other files.\n";
      for (const auto &f : manifest)
        out << f << '\n';
      out.close();
      if (out.fail())
        {
          const int       error = errno;
          std::error_code ec;
          fs::remove(tmp, ec);
          throw OutputError("Cannot write in the output directory " +
                            in_quotes(dir) + " (the file " + in_quotes(tmp) +
                            "): " + advice(error) + ".");
        }
    }
    std::error_code ec;
    fs::rename(tmp, dir / manifest_name, ec);
    if (ec)
      throw OutputError("Cannot write " + in_quotes(dir / manifest_name) +
                        ": " + advice(ec.value()) + ".");
  }



  void
  OutputDirectory::claim(const std::string &file)
  {
    // The watchdog's cleanup reads the manifest: not while it grows.
    const StopDeferral claiming;
    if (manifest.count(file) > 0)
      return;
    const fs::path dir(directory);
    for (const std::string suffix : {"", ".tmp"})
      {
        std::error_code ec;
        if (fs::exists(fs::symlink_status(dir / (file + suffix), ec)))
          throw OutputError(
            "The output directory " + in_quotes(dir) + " holds " +
            in_quotes(file + suffix) +
            ", which glide did not write; glide never overwrites a file it "
            "did not write. Move it away, or choose another 'Scene name' or "
            "'Output/Directory'.");
      }
    manifest.insert(file);
    write_manifest();
  }



  bool
  OutputDirectory::is_complete(const std::string &path,
                               const std::string &kind,
                               std::string       &message)
  {
    std::ifstream in(path, std::ios::binary);
    if (!in)
      {
        message = "cannot be read back";
        return false;
      }
    std::ostringstream s;
    s << in.rdbuf();
    const std::string text = s.str();
    if (text.empty())
      {
        message = "is empty";
        return false;
      }
    if (kind == ".vtu" || kind == ".pvd")
      {
        const auto end = text.find_last_not_of(" \n\r\t");
        if (end == std::string::npos || end < 9 ||
            text.compare(end - 9, 10, "</VTKFile>") != 0)
          {
            message = "does not end with </VTKFile> (cut short)";
            return false;
          }
      }
    if (kind == ".csv")
      {
        if (text.back() != '\n')
          {
            message = "does not end with a complete line (cut short)";
            return false;
          }
        std::istringstream lines(text);
        std::string        line;
        std::getline(lines, line);
        const auto columns = std::count(line.begin(), line.end(), ',');
        while (std::getline(lines, line))
          if (std::count(line.begin(), line.end(), ',') != columns)
            {
              message = "has a line with a different number of columns "
                        "than its header (cut short)";
              return false;
            }
      }
    return true;
  }



  void
  OutputDirectory::write_tmp(const std::string                         &file,
                             const std::function<void(std::ostream &)> &writer)
  {
    const StopDeferral writing;
    claim(file);
    const fs::path target = fs::path(directory) / file;
    const fs::path tmp    = fs::path(directory) / (file + ".tmp");
    int            error  = 0;
    {
      std::ofstream out(tmp, std::ios::binary);
      if (!out)
        error = errno ? errno : EIO;
      else
        {
          try
            {
              writer(out);
            }
          catch (const dealii::ExceptionBase &)
            {
              // deal.II's writers throw ExcIO when the stream fails.
              out.setstate(std::ios::badbit);
            }
          out.close();
          if (out.fail())
            error = errno ? errno : EIO;
        }
    }
    std::error_code ec;
    if (error != 0)
      {
        fs::remove(tmp, ec);
        throw OutputError("Cannot write " + in_quotes(target) + ": " +
                          advice(error) + ".");
      }
    std::string message;
    if (!is_complete(tmp.string(), kind_of(file), message))
      {
        fs::remove(tmp, ec);
        throw OutputError("Writing " + in_quotes(target) + " failed: it " +
                          message + "." +
                          (disk_full(directory) ?
                             " The disk is full: free space there or choose "
                             "another 'Output/Directory'." :
                             std::string("")));
      }
  }



  void
  OutputDirectory::rename_into_place(const std::string &from,
                                     const std::string &file)
  {
    std::error_code ec;
    fs::rename(from, fs::path(directory) / file, ec);
    if (ec)
      {
        std::error_code ignored;
        fs::remove(from, ignored);
        throw OutputError("Cannot rename '" + from + "' to " +
                          in_quotes(fs::path(directory) / file) + ": " +
                          advice(ec.value()) + ".");
      }
  }



  void
  OutputDirectory::write_file(const std::string                         &file,
                              const std::function<void(std::ostream &)> &writer)
  {
    write_tmp(file, writer);
    rename_into_place(directory + "/" + file + ".tmp", file);
  }



  void
  OutputDirectory::publish(const std::string &file)
  {
    const fs::path tmp = fs::path(directory) / (file + ".tmp");
    std::string    message;
    if (!is_complete(tmp.string(), kind_of(file), message))
      {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw OutputError("Writing " + in_quotes(fs::path(directory) / file) +
                          " failed: it " + message + "." +
                          (disk_full(directory) ?
                             " The disk is full: free space there or choose "
                             "another 'Output/Directory'." :
                             std::string("")));
      }
    rename_into_place(tmp.string(), file);
  }



  void
  OutputDirectory::write_index(
    const std::string                         &file,
    const std::function<void(std::ostream &)> &writer)
  {
    write_tmp(file, writer);
    pending_indexes.push_back(file);
  }



  void
  OutputDirectory::commit_step(const std::function<void()> &write_indexes)
  {
    const StopDeferral publishing;
    std::string        failure;
    if (root)
      try
        {
          std::vector<std::string> data, indexes;
          std::error_code          ec;
          for (const auto &e : fs::directory_iterator(staging_directory, ec))
            {
              const std::string f = e.path().filename().string();
              if (ends_with(f, ".tmp"))
                throw OutputError(
                  "Writing " + in_quotes(fs::path(directory) / f) +
                  " failed (its temporary file was left behind)" +
                  (disk_full(directory) ? "; the disk is full: free space "
                                          "there or choose another "
                                          "'Output/Directory'." :
                                          "."));
              (ends_with(f, ".pvd") ? indexes : data).push_back(f);
            }
          if (ec)
            throw OutputError("Cannot read " + in_quotes(staging_directory) +
                              ": " + advice(ec.value()) + ".");
          std::string message;
          for (const auto &f : data)
            if (!is_complete(staging_directory + "/" + f, kind_of(f), message))
              throw OutputError(
                "Writing " + in_quotes(fs::path(directory) / f) +
                " failed: it " + message + ". " +
                (disk_full(directory) ? "The disk is full: free space there or "
                                        "choose another 'Output/Directory'." :
                                        std::string("")));
          for (const auto &f : indexes)
            if (!is_complete(staging_directory + "/" + f, kind_of(f), message))
              throw OutputError("Writing " +
                                in_quotes(fs::path(directory) / f) +
                                " failed: it " + message + ".");
          // The writers of staged files do not check their streams: a
          // disk that is full now may have cut one of them short.
          if (disk_full(directory))
            throw OutputError("The disk of the output directory '" + directory +
                              "' is full: free space there or choose "
                              "another 'Output/Directory'.");
          for (const auto &f : data)
            claim(f);
          for (const auto &f : indexes)
            claim(f);
          for (const auto &f : data)
            {
              fs::rename(fs::path(staging_directory) / f,
                         fs::path(directory) / f,
                         ec);
              if (ec)
                throw OutputError("Cannot move " + f + " into " +
                                  in_quotes(directory) + ": " +
                                  advice(ec.value()) + ".");
            }
          // The indexes: first all written and checked under their
          // temporary names, then renamed one right after the other.
          // statistics.csv goes last: it is the step's commit record. A
          // SIGKILL between these renames (nothing can block it) leaves
          // .pvd files that list at most the one step statistics.csv
          // does not list yet, never fewer steps; whoever watches
          // statistics.csv (a job script, the fault tests) sees a step
          // only once every index lists it.
          pending_indexes.clear();
          write_indexes();
          const auto is_record = [](const std::string &f) {
            return ends_with(f, ".csv");
          };
          SignalBlocker blocker;
          for (const auto &f : pending_indexes)
            if (!is_record(f))
              rename_into_place(directory + "/" + f + ".tmp", f);
          for (const auto &f : indexes)
            rename_into_place(staging_directory + "/" + f, f);
          for (const auto &f : pending_indexes)
            if (is_record(f))
              rename_into_place(directory + "/" + f + ".tmp", f);
          pending_indexes.clear();
        }
      catch (const OutputError &e)
        {
          failure = e.what();
        }
      catch (const std::exception &e)
        {
          failure =
            std::string("Cannot write the results of this step: ") + e.what();
        }
    if (!failure.empty())
      {
        // Nothing of this step is published: its staged and temporary
        // files go.
        std::error_code ec;
        for (const auto &f : pending_indexes)
          fs::remove(fs::path(directory) / (f + ".tmp"), ec);
        pending_indexes.clear();
        for (const auto &e : fs::directory_iterator(staging_directory, ec))
          fs::remove(e.path(), ec);
      }
    throw_output_error_on_any_process(failure, comm);
  }
} // namespace glide
