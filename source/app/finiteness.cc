#include <deal.II/base/mpi.h>

#include <coulomb_adapt/app/finiteness.h>
#include <coulomb_adapt/core/units.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace coulomb_adapt
{
  namespace
  {
    // What to do about numbers outside the range of doubles: the static
    // problem with zero initial gap is positively homogeneous in the
    // loads (theory.md section 6), so units that keep them moderate give
    // the same epsilon.
    const std::string units_hint =
      "Give loads and moduli in units that keep stresses well inside "
      "1e-120 ... 1e120 (e.g. N, mm, MPa) relative to the moduli: loads "
      "and moduli beyond " +
      units::comfortable_range() +
      " MPa are scaled automatically, and with zero initial gap so are "
      "strains beyond " +
      units::comfortable_range() + " (theory.md section 6, Homogeneity).";

    std::string
    to_string(const double x)
    {
      std::ostringstream s;
      s.precision(3);
      s << x;
      return s.str();
    }

    // Largest |u_i| of a body over all ranks, and whether an entry is not
    // finite on any rank (a NaN would be lost in a max).
    std::pair<double, bool>
    displacement_range(const ElasticBody &body)
    {
      double max_abs    = 0;
      bool   non_finite = false;
      for (const auto i : body.locally_owned_dof_set())
        {
          const double u = body.solution()(i);
          if (!std::isfinite(u))
            non_finite = true;
          else
            max_abs = std::max(max_abs, std::abs(u));
        }
      const MPI_Comm comm = body.dof_handler().get_communicator();
      return {Utilities::MPI::max(max_abs, comm),
              Utilities::MPI::max(non_finite ? 1u : 0u, comm) > 0};
    }
  } // namespace



  void
  check_finite_solution(
    const std::array<std::unique_ptr<ElasticBody>, 2> &bodies,
    const ContactSolver                               *contact_solver)
  {
    for (unsigned int b = 0; b < 2; ++b)
      {
        const auto [max_abs, non_finite] = displacement_range(*bodies[b]);
        if (non_finite || max_abs > std::numeric_limits<double>::max() / 4)
          throw NonFiniteResult(
            "after the solve, the displacement of body " +
            std::to_string(b + 1) + " (" + bodies[b]->name() +
            ") is not finite (largest finite |u| = " + to_string(max_abs) +
            " mm). " + units_hint);
      }

    // Finite is not enough: the error indicator squares stresses and sums
    // the squares (and its recovery's CG the squares of residuals), so
    // stresses near 1e154 overflow there and near 1e-154 lose their digits
    // (blocks: a pressure of 1e152 gave epsilon = 100 % with exit 0,
    // 1e-152 a CG failure on a NaN residual). The stress scale
    // 2 mu max|u| / L must keep a wide margin from both ends.
    for (unsigned int b = 0; b < 2; ++b)
      {
        const ElasticBody &body    = *bodies[b];
        const double       max_abs = displacement_range(body).first;
        const double       size    = body.size();
        const double       stress_scale =
          size > 0 ? 2 * body.material().mu() * max_abs / size : 0;
        const double limit = units::accepted_stress;
        if (stress_scale > limit ||
            (stress_scale > 0 && stress_scale < 1 / limit))
          throw NonFiniteResult(
            "after the solve, the stresses of body " + std::to_string(b + 1) +
            " (" + body.name() + ") are of the order of " +
            to_string(stress_scale) +
            " MPa (2 mu max|u| / size, max|u| = " + to_string(max_abs) +
            " mm): outside 1e-120 ... 1e120 MPa, the "
            "error indicator's squares of stresses " +
            (stress_scale > limit ? "overflow" : "underflow") +
            " the range of doubles. " + units_hint);
      }

    if (contact_solver == nullptr)
      return;
    // Every rank holds every contact node: no communication needed.
    const std::vector<ContactNodeState> &nodes = contact_solver->node_states();
    for (const ContactNodeState &n : nodes)
      for (const auto &[quantity, value] :
           {std::pair<const char *, double>{"contact pressure", n.pressure},
            {"tangential traction", n.tangential_traction},
            {"gap", n.gap},
            {"slip", n.slip}})
        if (!std::isfinite(value))
          throw NonFiniteResult(
            std::string("after the contact solve, the ") + quantity +
            " at the contact node of body 1 (" + bodies[0]->name() + ") at (" +
            to_string(n.position[0]) + ", " + to_string(n.position[1]) +
            ") is " + to_string(value) + ". " + units_hint);
  }



  void
  check_finite_estimate(
    const std::array<std::unique_ptr<ElasticBody>, 2> &bodies,
    const ErrorEstimate                               &estimate)
  {
    const MPI_Comm comm = bodies[0]->dof_handler().get_communicator();
    for (unsigned int b = 0; b < 2; ++b)
      {
        // Element contributions e_E^2 (locally owned cells): an infinity or
        // NaN, or a subnormal number (the square of a stress below about
        // 1e-154 keeps few or no digits).
        unsigned int n_non_finite = 0, n_subnormal = 0;
        for (const double e : estimate.contribution_squared[b])
          if (!std::isfinite(e))
            ++n_non_finite;
          else if (e != 0 && std::abs(e) < std::numeric_limits<double>::min())
            ++n_subnormal;
        n_non_finite = Utilities::MPI::sum(n_non_finite, comm);
        n_subnormal  = Utilities::MPI::sum(n_subnormal, comm);
        const std::string body =
          "body " + std::to_string(b + 1) + " (" + bodies[b]->name() + ")";
        const double largest_u = displacement_range(*bodies[b]).first;
        if (n_non_finite > 0 || !std::isfinite(estimate.epsilon_volume[b]))
          throw NonFiniteResult(
            "the error indicator of " + body + " is not finite (" +
            std::to_string(n_non_finite) +
            " element contributions e_E^2, epsilon_volume = " +
            to_string(estimate.epsilon_volume[b]) +
            "): the squares of its stresses overflow the range of doubles "
            "(largest |u| = " +
            to_string(largest_u) + " mm). " + units_hint);
        if (n_subnormal > 0)
          throw NonFiniteResult(
            "the error indicator of " + body +
            " has lost its precision: " + std::to_string(n_subnormal) +
            " element contributions e_E^2 are below the smallest normal "
            "double (2.2e-308), the squares of its stresses underflow "
            "(largest |u| = " +
            to_string(largest_u) + " mm). " + units_hint);
      }

    const bool moves = displacement_range(*bodies[0]).first > 0 ||
                       displacement_range(*bodies[1]).first > 0;
    if (!std::isfinite(estimate.normalisation_squared) ||
        !std::isfinite(estimate.epsilon) ||
        !std::isfinite(estimate.epsilon_contact))
      throw NonFiniteResult(
        "the error indicator is not finite: D^2 = " +
        to_string(estimate.normalisation_squared) +
        " (the energy of the stresses), epsilon = " +
        to_string(estimate.epsilon) +
        ", epsilon_contact = " + to_string(estimate.epsilon_contact) +
        ": the squares of the stresses overflow the range of doubles. " +
        units_hint);
    if (moves &&
        estimate.normalisation_squared < std::numeric_limits<double>::min())
      throw NonFiniteResult(
        "the error indicator's normalisation D^2 (the energy of the "
        "stresses) is " +
        to_string(estimate.normalisation_squared) +
        " although the bodies move (largest |u| = " +
        to_string(std::max(displacement_range(*bodies[0]).first,
                           displacement_range(*bodies[1]).first)) +
        " mm): the squares of the stresses underflow the range of doubles, "
        "and epsilon would be meaningless. " +
        units_hint);
  }
} // namespace coulomb_adapt
