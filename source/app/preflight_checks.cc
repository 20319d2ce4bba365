#include <coulomb_adapt/app/preflight_checks.h>
#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/core/parameter_error.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace coulomb_adapt
{
  namespace
  {
    // The first meshes' DoFs, estimated from the coarse meshes: each
    // uniform refinement multiplies the cells by 4, and a P_p mesh has
    // about p^2 vertices' worth of DoFs per quadrilateral, half that per
    // triangle. On the way, each coarse mesh's cells are checked.
    double
    estimate_first_mesh_dofs(const Scene       &scene,
                             const Parameters  &parameters,
                             const std::string &mesh_source)
    {
      const unsigned int p        = parameters.finite_elements.degree;
      double             estimate = 0;
      for (unsigned int b = 0; b < 2; ++b)
        {
          Triangulation<2> coarse;
          scene.create_coarse_mesh(b, parameters.mesh.cell_type, coarse);
          // Degenerate cells, named with the file they come from
          // (ElasticBody checks every mesh it builds again, remeshed ones
          // too).
          try
            {
              check_mesh_cells(coarse, scene.describe_body(b).name, b);
            }
          catch (const std::exception &e)
            {
              throw ParameterError(mesh_source + e.what());
            }
          const double per_cell =
            (coarse.all_reference_cells_are_hyper_cube() ? 2. : 1.) * p * p;
          const double n_cells =
            coarse.n_active_cells() *
            std::pow(4., parameters.mesh.global_refinements);
          estimate += n_cells * per_cell;
          // The recovered stress of a single cell (its projection onto the
          // continuous space, or its patch fit) is the finite element
          // stress itself: the zz/spr indicator would be 0 whatever the
          // error.
          if (n_cells == 1 &&
              parameters.error_indicator.estimator != ErrorEstimator::cre)
            throw ParameterError(
              "Mesh/Global refinements",
              std::to_string(parameters.mesh.global_refinements),
              "body " + std::to_string(b + 1) + " (" +
                scene.describe_body(b).name +
                ") would have a single cell, on which the recovered stress "
                "of the '" +
                to_string(parameters.error_indicator.estimator) +
                "' estimator is the finite element stress itself: the "
                "error indicator would be 0 whatever the error. Give the "
                "body more cells (the scene's subdivisions) or refine once");
        }
      return estimate;
    }



    // The multipliers are differences of body 1's nodal forces, whose
    // terms are E1 / E_c times the contact force: their round-off, n eps
    // E1 / E_c of the pressure, reaches the largest 'Contact/Tolerance'
    // (1e-6) at a ratio of about 1e8. Body 2 may be the stiff one.
    void
    check_stiffness_ratio(const BodyDescription &body_1,
                          const BodyDescription &body_2)
    {
      const double E1 = body_1.material.youngs_modulus;
      const double E2 = body_2.material.youngs_modulus;
      if (body_1.contact_boundary_id == numbers::invalid_boundary_id ||
          body_2.contact_boundary_id == numbers::invalid_boundary_id ||
          E1 / E2 <= 1e8)
        return;
      std::ostringstream s;
      s << std::setprecision(3) << "body 1's Young's modulus (" << E1
        << " MPa) is " << E1 / E2 << " times body 2's (" << E2
        << " MPa): the contact pressures are differences of body 1's "
           "nodal forces, which would lose all their digits above a ratio "
           "of 1e8. Make the stiffer body body 2 (the lower one), or use "
           "moduli closer to each other";
      throw ParameterError(s.str());
    }



    // lambda / mu = 2 nu / (1 - 2 nu) is the ratio of the stiffness's
    // volumetric part to its shear part. Above 1e8 the shear response, the
    // one contact and the indicator need, is below the round-off of the
    // volumetric terms (as with the moduli above), and the Newton
    // iteration fails with a diagnosis about the contact sets that has
    // nothing to do with the cause (nu = 0.49999999999999994: "tips over an
    // edge" under a uniform pressure).
    void
    check_compressibility(const BodyDescription &body)
    {
      const double nu               = body.material.poissons_ratio;
      const double volumetric_ratio = 2 * nu / (1 - 2 * nu);
      const double largest_ratio    = 1e8;
      const double largest_poisson  = largest_ratio / (2 * (1 + largest_ratio));
      if (volumetric_ratio <= largest_ratio)
        return;
      std::ostringstream s;
      s << std::setprecision(17) << body.name << "'s Poisson's ratio " << nu
        << std::setprecision(3) << " makes lambda / mu = " << volumetric_ratio
        << ": its shear stiffness would be below the round-off of the "
           "volumetric one above a ratio of 1e8, and the displacement "
           "formulation (no mixed pressure here) would lose every digit of "
           "the response contact needs. Allowed: Poisson's ratio at most "
        << std::setprecision(10) << largest_poisson
        << " (and with degree 1 below about 0.49: linear elements lock)";
      throw ParameterError(s.str());
    }
  } // namespace



  // Unbounded work is refused before it starts: the first meshes must stay
  // below the DoF limit the adaptation keeps to (without this check, a
  // large 'Global refinements' ends in std::bad_alloc after minutes).
  void
  check_before_meshing(const Scene              &scene,
                       const Parameters         &parameters,
                       const std::string        &mesh_source,
                       const ConditionalOStream &pcout)
  {
    const double estimate =
      estimate_first_mesh_dofs(scene, parameters, mesh_source);
    const BodyDescription body_1 = scene.describe_body(0);
    const BodyDescription body_2 = scene.describe_body(1);
    check_stiffness_ratio(body_1, body_2);
    check_compressibility(body_1);
    check_compressibility(body_2);
    // Nearly incompressible bodies lock with P1 elements: the displacement
    // comes out too small and the indicator measures the locked solution.
    for (const BodyDescription *d : {&body_1, &body_2})
      if (d->material.poissons_ratio > 0.49 &&
          parameters.finite_elements.degree == 1)
        pcout << "warning: " << d->name << " has Poisson's ratio "
              << std::setprecision(10) << d->material.poissons_ratio
              << std::setprecision(6)
              << ": nearly incompressible, it locks with linear elements "
                 "(displacements too small, stresses oscillating); use "
                 "'Finite elements/Polynomial degree' = 2"
              << std::endl;
    if (estimate > parameters.adaptation.max_dofs &&
        parameters.mesh.global_refinements == 0)
      {
        // Nothing to lower: the scene's own meshes are above the limit.
        std::ostringstream s;
        s << "the scene's first meshes (no global refinement) would have "
             "about "
          << std::setprecision(3) << estimate
          << " DoFs, above this limit: raise it if the machine has the "
             "memory (about 1 kB per DoF), or give the scene coarser meshes";
        std::ostringstream limit;
        limit << parameters.adaptation.max_dofs;
        throw ParameterError("Adaptation/Maximum number of DoFs",
                             limit.str(),
                             s.str());
      }
    if (estimate > parameters.adaptation.max_dofs)
      {
        std::ostringstream s;
        s << "the first meshes would have about " << std::setprecision(3)
          << estimate << " DoFs, above 'Adaptation/Maximum number of DoFs' ("
          << parameters.adaptation.max_dofs
          << "): lower it, or raise that limit if the machine has the "
             "memory (about 1 kB per DoF)";
        throw ParameterError("Mesh/Global refinements",
                             std::to_string(parameters.mesh.global_refinements),
                             s.str());
      }
  }
} // namespace coulomb_adapt
