#include <glide/output/contact_output.h>

#include <deal.II/base/data_out_base.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <tuple>

namespace glide
{
  using namespace dealii;

  namespace
  {
    /// Rename @p from to @p to; on failure, the message naming both.
    std::string
    rename_file(const std::string &from, const std::string &to)
    {
      std::error_code error;
      std::filesystem::rename(from, to, error);
      return error ? "cannot rename '" + from + "' to '" + to +
                       "': " + error.message() :
                     "";
    }
  } // namespace

  template <int dim>
  ContactWriter<dim>::ContactWriter(const std::string &directory)
    : directory(directory)
  {}

  template <int dim>
  std::string
  ContactWriter<dim>::write(const std::vector<ContactPairFields<dim>> &pairs,
                            const unsigned int                         step,
                            const double                               time,
                            const bool                                 vtu)
  {
    char number[16];
    std::snprintf(number, sizeof(number), "%04u", step);
    const char *X[] = {"X", "Y", "Z"}, *x[] = {"x", "y", "z"};
    for (const auto &pair : pairs)
      {
        const std::string stem = directory + "/contact-" + pair.pair;

        // CSV: one row per slave node.
        const std::string csv = stem + "-" + number + ".csv";
        {
          std::ofstream out(csv + ".tmp");
          out.precision(12);
          for (unsigned int d = 0; d < dim; ++d)
            out << X[d] << ",";
          for (unsigned int d = 0; d < dim; ++d)
            out << x[d] << ",";
          out << "COPEN,force,CPRESS,CSTATUS,CSLIP";
          for (unsigned int a = 0; a < dim - 1; ++a)
            out << ",CSLIP" << a + 1;
          out << "\n";
          for (const auto &n : pair.nodes)
            {
              for (unsigned int d = 0; d < dim; ++d)
                out << n.X[d] << ",";
              for (unsigned int d = 0; d < dim; ++d)
                out << n.x[d] << ",";
              out << n.COPEN << "," << n.force << "," << n.CPRESS << ","
                  << n.CSTATUS << "," << n.CSLIP;
              for (unsigned int a = 0; a < dim - 1; ++a)
                out << "," << n.CSLIP_components[a];
              out << "\n";
            }
          out.close();
          if (!out)
            return "cannot write '" + csv + ".tmp'";
        }
        if (const auto e = rename_file(csv + ".tmp", csv); !e.empty())
          return e;

        if (!vtu)
          continue;
        // VTU: the slave nodes as points at their reference positions,
        // with the contact fields and the displacement (for Warp By
        // Vector).
        const unsigned int n_fields = 5 + 2 * dim + (dim - 1) * (dim + 1);
        std::vector<DataOutBase::Patch<0, dim>> patches;
        for (const auto &n : pair.nodes)
          {
            DataOutBase::Patch<0, dim> patch;
            patch.vertices[0] = n.X;
            patch.data.reinit(n_fields, 1);
            const double scalars[] = {
              n.COPEN, n.force, n.CPRESS, n.CSTATUS, n.CSLIP};
            unsigned int j = 0;
            for (const double v : scalars)
              patch.data(j++, 0) = v;
            for (unsigned int d = 0; d < dim; ++d)
              patch.data(j++, 0) = n.normal[d];
            for (unsigned int d = 0; d < dim; ++d)
              patch.data(j++, 0) = n.x[d] - n.X[d];
            for (const auto &t : n.tangents)
              for (unsigned int d = 0; d < dim; ++d)
                patch.data(j++, 0) = t[d];
            for (unsigned int a = 0; a < dim - 1; ++a)
              patch.data(j++, 0) = n.CSLIP_components[a];
            patch.patch_index = patches.size();
            patches.push_back(patch);
          }
        std::vector<std::string> names{
          "COPEN", "force", "CPRESS", "CSTATUS", "CSLIP"};
        for (unsigned int d = 0; d < dim; ++d)
          names.push_back("contact_normal");
        for (unsigned int d = 0; d < dim; ++d)
          names.push_back("displacement");
        for (unsigned int a = 0; a < dim - 1; ++a)
          for (unsigned int d = 0; d < dim; ++d)
            names.push_back("tangent" + std::to_string(a + 1));
        for (unsigned int a = 0; a < dim - 1; ++a)
          names.push_back("CSLIP" + std::to_string(a + 1));
        std::vector<
          std::tuple<unsigned int,
                     unsigned int,
                     std::string,
                     DataComponentInterpretation::DataComponentInterpretation>>
          vectors{{5,
                   5 + dim - 1,
                   "contact_normal",
                   DataComponentInterpretation::component_is_part_of_vector},
                  {5 + dim,
                   5 + 2 * dim - 1,
                   "displacement",
                   DataComponentInterpretation::component_is_part_of_vector}};
        for (unsigned int a = 0; a < dim - 1; ++a)
          vectors.emplace_back(
            5 + 2 * dim + a * dim,
            5 + 2 * dim + a * dim + dim - 1,
            "tangent" + std::to_string(a + 1),
            DataComponentInterpretation::component_is_part_of_vector);
        const std::string file = "contact-" + pair.pair + "-" + number + ".vtu";
        {
          std::ofstream         out(directory + "/" + file + ".tmp");
          DataOutBase::VtkFlags flags(time);
          flags.compression_level = DataOutBase::VtkFlags::best_speed;
          DataOutBase::write_vtu(patches, names, vectors, flags, out);
          if (!out)
            throw std::runtime_error("cannot write '" + directory + "/" + file +
                                     ".tmp'");
        }
        rename_file(directory + "/" + file + ".tmp", directory + "/" + file);
        auto &list = records[pair.pair];
        list.emplace_back(time, file);
        {
          std::ofstream out(stem + ".pvd.tmp");
          DataOutBase::write_pvd_record(out, list);
          out.close();
          if (!out)
            return "cannot write '" + stem + ".pvd.tmp'";
        }
        if (const auto e = rename_file(stem + ".pvd.tmp", stem + ".pvd");
            !e.empty())
          return e;
      }
    return "";
  }

  template class ContactWriter<2>;
  template class ContactWriter<3>;
} // namespace glide
