#include <glide/output/output_error.h>
#include <glide/output/vtu_writer.h>

#include <deal.II/base/mpi.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

namespace glide
{
  using namespace dealii;

  namespace
  {
    /// Strain, stress and von Mises stress from the displacement field,
    /// with each body's own law.
    template <int dim>
    class StressPostprocessor : public DataPostprocessor<dim>
    {
    public:
      explicit StressPostprocessor(const Elasticity<dim> &elasticity)
        : elasticity(elasticity)
        , axisymmetric(elasticity.get_scene().analysis ==
                       AnalysisType::axisymmetric)
      {
        for (unsigned int b = 0; b < elasticity.get_scene().bodies.size(); ++b)
          laws.push_back(elasticity.material(b));
      }

      std::vector<std::string>
      get_names() const override
      {
        std::vector<std::string> n(dim * dim, "strain");
        n.insert(n.end(), dim * dim, "stress");
        if (dim == 2)
          {
            n.push_back(axisymmetric ? "strain_hoop" : "strain_zz");
            n.push_back(axisymmetric ? "stress_hoop" : "stress_zz");
          }
        n.push_back("von_Mises");
        return n;
      }

      std::vector<DataComponentInterpretation::DataComponentInterpretation>
      get_data_component_interpretation() const override
      {
        std::vector<DataComponentInterpretation::DataComponentInterpretation> i(
          2 * dim * dim,
          DataComponentInterpretation::component_is_part_of_tensor);
        i.insert(i.end(),
                 dim == 2 ? 3 : 1,
                 DataComponentInterpretation::component_is_scalar);
        return i;
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_values | update_gradients | update_quadrature_points;
      }

      void
      evaluate_vector_field(
        const DataPostprocessorInputs::Vector<dim> &inputs,
        std::vector<Vector<double>>                &computed) const override
      {
        const auto cell = inputs.template get_cell<dim>();
        Material  &law  = *laws[cell->material_id()];
        for (unsigned int q = 0; q < computed.size(); ++q)
          {
            Tensor2 H;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                H[i][j] = inputs.solution_gradients[q][i][j];
            if (dim == 2 && axisymmetric)
              {
                const double r = inputs.evaluation_points[q][0];
                H[2][2] = r > 0 ? inputs.solution_values[q][0] / r : H[0][0];
              }
            // At finite strain the converged solution keeps det F > 0 at
            // the quadrature points; at an output point (a vertex) of a
            // strongly distorted cell it may not. The stress is undefined
            // there: written as NaN and counted (the step ended the run
            // with "inverted element" after it had converged).
            Tensor2 sigma;
            Tensor2 F = H;
            for (unsigned int i = 0; i < 3; ++i)
              F[i][i] += 1.;
            if (law.finite_strain() && !(determinant(F) > 0.))
              {
                ++inverted;
                for (unsigned int i = 0; i < 3; ++i)
                  for (unsigned int j = 0; j < 3; ++j)
                    sigma[i][j] = std::numeric_limits<double>::quiet_NaN();
              }
            else
              {
                Tensor2 P;
                law.evaluate(H, P);
                sigma = law.cauchy_stress();
              }
            // Small strain, or Green-Lagrange strain at finite strain.
            Tensor2 E = 0.5 * (H + transpose(H));
            if (law.finite_strain())
              E += 0.5 * transpose(H) * H;
            unsigned int k = 0;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                computed[q](k++) = E[i][j];
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                computed[q](k++) = sigma[i][j];
            if (dim == 2)
              {
                computed[q](k++) = E[2][2];
                computed[q](k++) = sigma[2][2];
              }
            const Tensor2 dev =
              sigma - (trace(sigma) / 3.) * unit_symmetric_tensor<3>();
            computed[q](k++) = std::sqrt(1.5 * scalar_product(dev, dev));
          }
      }

      /// Output points where det F <= 0 (stress written as NaN).
      mutable std::atomic<unsigned int> inverted{0};

    private:
      const Elasticity<dim>                         &elasticity;
      const bool                                     axisymmetric;
      mutable std::vector<std::unique_ptr<Material>> laws;
    };
  } // namespace

  template <int dim>
  VtuWriter<dim>::VtuWriter(const Elasticity<dim> &elasticity,
                            OutputDirectory       &output,
                            const std::string     &name)
    : elasticity(elasticity)
    , output(output)
    , name(name)
  {}

  template <int dim>
  void
  VtuWriter<dim>::write(const unsigned int step,
                        const double       time,
                        const VectorType  &U,
                        const VectorType  *contact_force)
  {
    const auto      &dof_handler = elasticity.get_dof_handler();
    const auto       comm = elasticity.get_triangulation().get_communicator();
    const VectorType U_ghost = elasticity.ghosted_displacement(U);

    DataOut<dim> data_out;
    data_out.attach_dof_handler(dof_handler);
    // zlib's fastest level: deal.II's default, its best compression, took
    // 45 % of a 2D Hertz run (parameters/hertz-2d.prm, 33 612 DoFs, 4
    // steps: 5.6 of 12.4 s; 0.56 s with this) for files 3 % smaller.
    DataOutBase::VtkFlags flags;
    flags.compression_level = DataOutBase::VtkFlags::best_speed;
    data_out.set_flags(flags);
    const auto add_vector_field = [&](const VectorType  &v,
                                      const std::string &field) {
      data_out.add_data_vector(
        v,
        std::vector<std::string>(dim, field),
        DataOut<dim>::type_dof_data,
        std::vector<DataComponentInterpretation::DataComponentInterpretation>(
          dim, DataComponentInterpretation::component_is_part_of_vector));
    };
    add_vector_field(U_ghost, "displacement");
    StressPostprocessor<dim> stress(elasticity);
    data_out.add_data_vector(U_ghost, stress);
    VectorType force_ghost;
    if (contact_force)
      {
        force_ghost = elasticity.ghosted_displacement(*contact_force);
        add_vector_field(force_ghost, "contact_force");
      }
    const auto   &tria = elasticity.get_triangulation();
    Vector<float> material(tria.n_active_cells()),
      subdomain(tria.n_active_cells());
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          material(cell->active_cell_index())  = cell->material_id();
          subdomain(cell->active_cell_index()) = cell->subdomain_id();
        }
    data_out.add_data_vector(material, "material_id");
    data_out.add_data_vector(subdomain, "subdomain");
    const unsigned int degree = elasticity.get_scene().degree;
    data_out.build_patches(elasticity.get_mapping(),
                           degree,
                           DataOut<dim>::curved_inner_cells);
    last_inverted = Utilities::MPI::sum(stress.inverted.load(), comm);

    char number[16];
    std::snprintf(number, sizeof(number), "%04u", step);
    const std::string file = name + "-" + number + ".vtu";
    const std::string tmp  = output.path() + "/" + file + ".tmp";
    const bool        root = Utilities::MPI::this_mpi_process(comm) == 0;
    std::string       failure;
    if (root)
      try
        {
          output.claim(file);
        }
      catch (const std::exception &e)
        {
          failure = e.what();
        }
    throw_output_error_on_any_process(failure, comm);
    try
      {
        if (Utilities::MPI::n_mpi_processes(comm) == 1)
          {
            // One process: a stream whose state tells whether the disk
            // took every byte.
            errno = 0;
            std::ofstream out(tmp, std::ios::binary);
            data_out.write_vtu(out);
            out.close();
            if (out.fail())
              failure = "Cannot write '" + output.path() + "/" + file +
                        "': " + advice(errno ? errno : EIO) + ".";
          }
        else
          {
            // MPI-IO does not set errno.
            errno = 0;
            data_out.write_vtu_in_parallel(tmp, comm);
          }
      }
    catch (const std::exception &)
      {
        // deal.II checks the stream itself (ExcIO): errno still tells why
        // (one process).
        const int error =
          Utilities::MPI::n_mpi_processes(comm) == 1 ? errno : 0;
        failure = "Cannot write '" + output.path() + "/" + file +
                  "': " + (error != 0 ? advice(error) : "(is the disk full?)") +
                  ".";
      }
    if (root && !failure.empty())
      {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
      }
    throw_output_error_on_any_process(failure, comm);
    if (root)
      try
        {
          output.publish(file);
          records.emplace_back(time, file);
        }
      catch (const std::exception &e)
        {
          failure = e.what();
        }
    throw_output_error_on_any_process(failure, comm);
  }

  template <int dim>
  void
  VtuWriter<dim>::write_pvd()
  {
    if (records.empty())
      return;
    output.write_index(name + ".pvd", [&](std::ostream &out) {
      DataOutBase::write_pvd_record(out, records);
    });
  }

  template class VtuWriter<2>;
  template class VtuWriter<3>;
} // namespace glide
