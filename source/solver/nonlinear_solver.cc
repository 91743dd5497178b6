#include <glide/output/interruption.h>
#include <glide/output/output_error.h>
#include <glide/scene/input_error.h>
#include <glide/solver/nonlinear_solver.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/sundials/kinsol.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <new>
#include <sstream>

namespace glide
{
  using namespace dealii;

  namespace
  {
    /**
     * KINSOL (SUNDIALS 6) prints its failures ("[KINSOL ERROR]  KINSol /
     * The line search algorithm was unable to ...") to the C stream that
     * `stderr` is when its memory is created, inside deal.II's
     * KINSOL::solve(), which gives no access to KINSetErrFile(). A failed
     * attempt is a normal event that glide retries and reports in its own
     * log, so while a solve runs `stderr` is a stream in memory (glibc
     * lets it be assigned); release() restores it and returns the text.
     * File descriptor 2 stays as it is, so the C library's own fatal
     * messages and C++'s std::cerr still reach the terminal at once.
     */
    class CapturedStderr
    {
    public:
      CapturedStderr()
      {
#ifdef __GLIBC__
        std::fflush(stderr);
        stream = open_memstream(&buffer, &size);
        if (stream != nullptr)
          {
            saved  = stderr;
            stderr = stream;
          }
#endif
      }

      CapturedStderr(const CapturedStderr &) = delete;
      CapturedStderr &
      operator=(const CapturedStderr &) = delete;

      /// Restore stderr; what was written to it meanwhile.
      std::string
      release()
      {
        std::string text;
#ifdef __GLIBC__
        if (stream == nullptr)
          return text;
        stderr = saved;
        std::fclose(stream);
        stream = nullptr;
        if (buffer != nullptr)
          text.assign(buffer, size);
        std::free(buffer);
        buffer = nullptr;
#endif
        return text;
      }

      /// On an exception: restore stderr, and pass on what was captured.
      ~CapturedStderr()
      {
        const std::string text = release();
        std::fputs(text.c_str(), stderr);
      }

    private:
      FILE       *stream = nullptr;
      FILE       *saved  = nullptr;
      char       *buffer = nullptr;
      std::size_t size   = 0;
    };

    /**
     * Split text written to stderr into KINSOL's messages (each block
     * "[KINSOL ERROR]  <function>\n  <message>\n\n", or WARNING), returned
     * as the messages themselves joined by "; ", and anything else, left in
     * @p text.
     */
    std::string
    take_kinsol_messages(std::string &text)
    {
      std::string messages, rest;
      std::size_t at = 0;
      while (at < text.size())
        {
          const std::size_t start = text.find("[KINSOL ", at);
          if (start == std::string::npos)
            {
              rest += text.substr(at);
              break;
            }
          // Less the blank line KINSOL writes before each message.
          const bool blank = start > at && text[start - 1] == '\n';
          rest += text.substr(at, start - at - (blank ? 1 : 0));
          const std::size_t header_end = text.find('\n', start);
          if (header_end == std::string::npos)
            {
              at = text.size();
              break;
            }
          std::size_t end = text.find("\n\n", header_end + 1);
          if (end == std::string::npos)
            end = text.size();
          std::string message =
            text.substr(header_end + 1, end - header_end - 1);
          const auto first = message.find_first_not_of(" \n");
          const auto last  = message.find_last_not_of(" \n");
          message          = first == std::string::npos ?
                               std::string() :
                               message.substr(first, last - first + 1);
          if (!message.empty())
            messages += (messages.empty() ? "" : "; ") + message;
          at = end + (end < text.size() ? 2 : 0);
        }
      // What surrounded the blocks: only the blank lines KINSOL adds?
      if (rest.find_first_not_of(" \n") == std::string::npos)
        rest.clear();
      text = rest;
      return messages;
    }
  } // namespace

  NonlinearSolver::NonlinearSolver(const NonlinearSolverParameters &parameters,
                                   MPI_Comm                         comm)
    : parameters(parameters)
    , comm(comm)
  {}

  NonlinearSolver::Result
  NonlinearSolver::solve(VectorType      &U,
                         const Callbacks &cb,
                         const double     residual_scale,
                         const double     solution_scale)
  {
    VectorType f_scale, u_scale;
    cb.reinit_vector(f_scale);
    cb.reinit_vector(u_scale);
    f_scale = residual_scale;
    u_scale = solution_scale;
    return solve(U, cb, f_scale, u_scale);
  }

  NonlinearSolver::Result
  NonlinearSolver::solve(VectorType       &U,
                         const Callbacks  &cb,
                         const VectorType &residual_scale,
                         const VectorType &solution_scale)
  {
    using KINSOL = SUNDIALS::KINSOL<VectorType>;
    // The longest Newton step KINSOL takes, in the scaled 2-norm
    // ||D_u du||_2 (D_u = 1 / scene size). KINSOL's default (0 here),
    // 1000 ||D_u u_0||_2 or 1000 from u_0 = 0, cut every step of a
    // geometrically linear block loaded to a strain of a few hundred short:
    // its residual fell by 0.15 % per iteration until KINSOL stopped on its
    // step length test, where one full step solves the problem. A linear
    // problem therefore gets a root-mean-square motion of 1e8 scene sizes,
    // the limit of the input checks (Elasticity::check_inputs). With
    // contact the default stays: it shortens the first step of a body held
    // only by contact, whose Newton direction can be wild (the 3D Hertz
    // sphere across its refinement border: 10 iterations in the first step
    // without it, 7 with it).
    const double maximum_step =
      parameters.linear_problem ?
        1e8 * std::sqrt(std::max<double>(1., U.size())) :
        0.;
    typename KINSOL::AdditionalData data(parameters.strategy == "newton" ?
                                           KINSOL::AdditionalData::newton :
                                           KINSOL::AdditionalData::linesearch,
                                         parameters.maximum_iterations,
                                         parameters.tolerance,
                                         parameters.step_tolerance,
                                         /*no_init_setup=*/false,
                                         parameters.maximum_setup_calls,
                                         maximum_step);
    KINSOL kinsol(data, comm);

    Result      result;
    std::string failure; // set by a callback that failed
    bool        setup_failed = false;
    // The previous iterate's scaled residual, and whether the solve ended
    // because the residual stalled within the round-off floor.
    double       last_norm        = std::numeric_limits<double>::infinity();
    bool         stalled_at_floor = false;
    unsigned int stopped_after    = 0;
    VectorType   f_scale = residual_scale, u_scale = solution_scale;
    // Scaled max-norm ||D_F F||_inf, KINSOL's measure of convergence.
    auto scaled_norm = [&](const VectorType &F) {
      VectorType scaled = F;
      scaled.scale(residual_scale);
      return scaled.linfty_norm();
    };

    // Exceptions must not cross KINSOL's C code: callbacks catch them and
    // return KINSOL's "recoverable" (1) or "fatal" (-1) codes instead.
    // Errors that no retry can cure (an input error found while
    // evaluating a function of the scene, an output error, a stop signal)
    // end the solve and are rethrown after it.
    std::exception_ptr fatal;
    kinsol.reinit_vector = cb.reinit_vector;
    kinsol.residual      = [&](const VectorType &u, VectorType &F) -> int {
      try
        {
          throw_if_interrupted(comm);
          cb.residual(u, F);
          // NaN or infinity: no step can mend it (KINSOL's line search
          // would shrink the step forever).
          if (!std::isfinite(F.linfty_norm()))
            {
              failure = "the residual is not finite (NaN or infinity)";
              return -1;
            }
          return 0;
        }
      catch (const InputError &)
        {
          fatal = std::current_exception();
          return -1;
        }
      catch (const Interrupted &)
        {
          fatal = std::current_exception();
          return -1;
        }
      catch (const std::bad_alloc &)
        {
          // Out of memory: no smaller load step mends that.
          fatal = std::current_exception();
          return -1;
        }
      catch (const std::exception &e)
        {
          failure = e.what();
          return 1;
        }
    };
    kinsol.setup_jacobian = [&](const VectorType &u,
                                const VectorType &F) -> int {
      try
        {
          const double norm = scaled_norm(F);
          cb.report(result.iterations, norm);
          // Above the tolerance but within the round-off floor, and no
          // longer falling as Newton falls (by a factor 10 or more per
          // iteration near a root): round-off is all that is left to
          // reduce, and more iterations only repeat it (a contact zone 1e5
          // from the origin stalled at 5.5e-10 to 8.9e-10 for 15
          // iterations). End the solve at this iterate; it counts as at
          // the floor below.
          if (norm > parameters.tolerance &&
              norm <= parameters.round_off_floor &&
              last_norm <= parameters.round_off_floor && norm > 0.1 * last_norm)
            {
              stalled_at_floor = true;
              stopped_after    = result.iterations;
              setup_failed     = true;
              return -1;
            }
          last_norm = norm;
          ++result.iterations;
          setup_failed = false;
          cb.setup_jacobian(u);
          return 0;
        }
      catch (const std::exception &e)
        {
          // deal.II 9.4.1 ignores this return value: remember the failure
          // so that the next linear solve refuses to run.
          if (dynamic_cast<const InputError *>(&e) ||
              dynamic_cast<const Interrupted *>(&e) ||
              dynamic_cast<const std::bad_alloc *>(&e))
            fatal = std::current_exception();
          failure      = e.what();
          setup_failed = true;
          return -1;
        }
    };
    kinsol.solve_with_jacobian =
      [&](const VectorType &rhs, VectorType &dst, const double) -> int {
      if (setup_failed)
        return -1;
      try
        {
          result.linear_iterations += cb.solve_jacobian(rhs, dst);
          if (!std::isfinite(dst.linfty_norm()))
            {
              failure = "the Newton update is not finite (NaN or infinity): "
                        "the Jacobian is singular or overflows";
              return -1;
            }
          return 0;
        }
      catch (const std::exception &e)
        {
          if (dynamic_cast<const std::bad_alloc *>(&e))
            fatal = std::current_exception();
          failure = e.what();
          return -1;
        }
    };
    kinsol.get_function_scaling = [&]() -> VectorType & { return f_scale; };
    kinsol.get_solution_scaling = [&]() -> VectorType & { return u_scale; };

    VectorType  guess = U;
    std::string kinsol_says; // KINSOL's own reason for stopping
    {
      CapturedStderr captured;
      try
        {
          // KINSOL's own count of nonlinear iterations (setups may be fewer
          // when the Jacobian is reused).
          result.iterations = kinsol.solve(U);
        }
      catch (const ExceptionBase &e)
        {
          // Debug builds of deal.II throw on a KINSOL failure.
          std::ostringstream s;
          e.print_info(s);
          if (failure.empty())
            failure = s.str();
        }
      std::string text = captured.release();
      kinsol_says      = take_kinsol_messages(text);
      // Anything else (another library's warning) goes where it was sent.
      std::fputs(text.c_str(), stderr);
    }

    // KINSOL also counts the iteration it could not complete.
    if (stalled_at_floor)
      result.iterations = stopped_after;
    if (fatal)
      {
        U = guess;
        std::rethrow_exception(fatal);
      }

    // Explicit convergence check (release builds do not report failure).
    VectorType F;
    cb.reinit_vector(F);
    try
      {
        cb.residual(U, F);
        result.residual_norm = scaled_norm(F);
      }
    catch (const std::exception &e)
      {
        result.residual_norm = std::numeric_limits<double>::infinity();
        if (failure.empty())
          failure = e.what();
      }
    result.converged = std::isfinite(result.residual_norm) &&
                       result.residual_norm <= parameters.tolerance;
    // KINSOL stopped (line search, step tolerance or iteration limit) with
    // a residual that round-off alone can leave: as converged as this
    // arithmetic allows.
    if (!result.converged && (failure.empty() || stalled_at_floor) &&
        std::isfinite(result.residual_norm) &&
        result.residual_norm <= parameters.round_off_floor)
      {
        result.converged = true;
        result.at_floor  = true;
      }
    if (!result.converged)
      {
        std::ostringstream s;
        if (!failure.empty())
          s << failure;
        else if (result.iterations >= parameters.maximum_iterations)
          s << "no convergence in " << parameters.maximum_iterations
            << " Newton iterations (scaled residual " << result.residual_norm
            << " > tolerance " << parameters.tolerance << ")";
        else if (!kinsol_says.empty())
          s << "KINSOL stopped with scaled residual " << result.residual_norm
            << " > tolerance " << parameters.tolerance << ": " << kinsol_says;
        else
          s << "KINSOL stopped with scaled residual " << result.residual_norm
            << " > tolerance " << parameters.tolerance
            << " (line search or step tolerance)";
        result.message = s.str();
        U              = guess;
      }
    else if (result.iterations == 0)
      cb.report(0, result.residual_norm);
    return result;
  }
} // namespace glide
