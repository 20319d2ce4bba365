#include <deal.II/base/mpi.h>

#include <coulomb_adapt/app/load_scaling.h>
#include <coulomb_adapt/contact/mortar_interface.h>

#include <cmath>
#include <limits>

namespace coulomb_adapt
{
  namespace
  {
    // The largest |component|: the Euclidean norm squares them, which
    // underflows for loads of 1e-300 and overflows for 1e300.
    double
    magnitude(const Tensor<1, 2> &t)
    {
      return std::max(std::abs(t[0]), std::abs(t[1]));
    }

    // Largest value of each kind of load of one body at the current load
    // step: 0 traction, 1 body force times size, 2 E u_D / size.
    std::array<double, 3>
    load_maxima(const ElasticBody &body, const double size)
    {
      std::array<double, 3>  maxima = {{0, 0, 0}};
      const BodyDescription &d      = body.description();
      const double           E      = d.material.youngs_modulus;
      Vector<double>         u_D(2);
      for (const auto &cell : body.triangulation().active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          if (d.body_force)
            maxima[1] =
              std::max(maxima[1],
                       magnitude(d.body_force(cell->center())) * size);
          for (const unsigned int f : cell->face_indices())
            {
              if (!cell->face(f)->at_boundary())
                continue;
              const auto               face      = cell->face(f);
              const types::boundary_id id        = face->boundary_id();
              const Point<2>           points[3] = {face->vertex(0),
                                                    face->vertex(1),
                                                    face->center()};
              // The outward normal of the face's chord.
              const Tensor<1, 2> tangent = face->vertex(1) - face->vertex(0);
              Tensor<1, 2>       normal;
              normal[0] = tangent[1];
              normal[1] = -tangent[0];
              normal /= normal.norm();
              if (normal * (face->center() - cell->center()) < 0)
                normal *= -1;
              for (const auto &t : d.tractions)
                if (t.boundary_id == id)
                  for (const Point<2> &x : points)
                    maxima[0] =
                      std::max(maxima[0], magnitude(t.traction(x, normal)));
              for (const auto &dirichlet : d.dirichlet)
                if (dirichlet.boundary_id == id)
                  for (const Point<2> &x : points)
                    {
                      dirichlet.displacement->vector_value(x, u_D);
                      for (unsigned int c = 0; c < 2; ++c)
                        if (dirichlet.components[c])
                          maxima[2] =
                            std::max(maxima[2], E * (std::abs(u_D[c]) / size));
                    }
            }
        }
      return maxima;
    }
  } // namespace



  LoadStressScale
  load_stress_scale(const Scene                                       &scene,
                    const std::array<std::unique_ptr<ElasticBody>, 2> &bodies)
  {
    const MPI_Comm        comm  = bodies[0]->dof_handler().get_communicator();
    std::array<double, 2> sizes = {{bodies[0]->size(), bodies[1]->size()}};
    // [body][kind], over the load steps.
    std::array<std::array<double, 3>, 2> maxima  = {};
    const unsigned int                   n_steps = scene.n_load_steps();
    for (unsigned int step = 1; step <= n_steps; ++step)
      {
        if (n_steps > 1)
          scene.set_load_step(step);
        for (unsigned int b = 0; b < 2; ++b)
          {
            const auto m = load_maxima(*bodies[b], sizes[b]);
            for (unsigned int k = 0; k < 3; ++k)
              maxima[b][k] = std::max(maxima[b][k], m[k]);
          }
      }
    if (n_steps > 1)
      scene.set_load_step(1);

    LoadStressScale result;
    result.size          = std::max(sizes[0], sizes[1]);
    const char *kinds[3] = {"the traction on the boundary",
                            "the body force times the body's size",
                            "Young's modulus times the prescribed "
                            "displacement over the body's size"};
    for (unsigned int b = 0; b < 2; ++b)
      for (unsigned int k = 0; k < 3; ++k)
        {
          // A NaN is no scale (the parameters exclude it); max keeps it out.
          const double m = Utilities::MPI::max(maxima[b][k], comm);
          if (m > result.stress)
            {
              result.stress = m;
              result.where  = std::string(kinds[k]) + " of body " +
                             std::to_string(b + 1) + " (" + bodies[b]->name() +
                             ")";
            }
        }
    return result;
  }



  // Every rank holds the whole interface: no communication needed.
  double
  largest_initial_gap(const std::array<std::unique_ptr<ElasticBody>, 2> &bodies)
  {
    MortarInterface mortar;
    mortar.reinit(*bodies[0], *bodies[1]);
    double largest = 0;
    for (unsigned int j = 0; j < mortar.slave_nodes().size(); ++j)
      if (mortar.is_covered(j))
        largest = std::max(largest,
                           std::abs(mortar.weighted_initial_gaps()[j] /
                                    mortar.slave_weights()[j]));
    return largest;
  }
} // namespace coulomb_adapt
