#ifndef coulomb_adapt_indicator_local_problem_loads_h
#define coulomb_adapt_indicator_local_problem_loads_h

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/indicator/equilibrated_stress.h>
#include <coulomb_adapt/indicator/equilibration_mesh.h>
#include <coulomb_adapt/indicator/local_neumann_problem.h>

#include <map>
#include <vector>

namespace coulomb_adapt
{
  namespace equilibration
  {
    /**
     * The loads of the cells' local Neumann problems in the element
     * equilibration: on each face the traction eta F (F from the face's
     * nodal coefficients (the classical moments), eta = +1 on the face's plus
     * cell and -1 on the other) where the moments were solved for, the
     * prescribed traction elsewhere on the boundary, the contact traction, a
     * held line's traction (held_reactions.h), and the body force. Also the
     * work of a face's traction basis on a cell's monomials, which the
     * optimisation of the free parameters needs.
     *
     * Read-only: several threads may use one object, each with its own
     * LocalNeumannProblem.
     */
    class LocalProblemLoads
    {
    public:
      LocalProblemLoads(const BodyDescription       &description,
                        const std::vector<CellData> &cells,
                        const std::vector<FaceData> &faces,
                        const ContactTractionData   &contact,
                        const unsigned int           fe_degree,
                        const unsigned int           local_degree);

      /** The whole load of cell @p slot; @p local must be reinit'ed on
       * that cell. */
      void
      cell_load(const LocalNeumannProblem &local,
                const unsigned int         slot,
                Vector<double>            &load) const;

      /** W(m, j): the work of the traction basis j of @p face (its n nodal
       * polynomials, then the bubble of degree p + 1, then the linear and
       * the quadratic Legendre polynomials: columns n, n + 1, n + 2), with
       * cell @p slot's orientation, on monomial m of @p local. */
      void
      face_work(const LocalNeumannProblem &local,
                const unsigned int         slot,
                const FaceData            &face,
                FullMatrix<double>        &W) const;

    private:
      // The traction sign * (the polynomial of @p face with nodal
      // @p coefficients) on the components in @p mask: eta F from the
      // face's coefficients, or a held line's g.
      void
      add_face_polynomial(
        const LocalNeumannProblem                &local,
        Vector<double>                           &load,
        const FaceData                           &face,
        const std::vector<std::array<double, 2>> &coefficients,
        const double                              sign,
        const std::array<bool, 2>                &mask) const;

      const std::vector<CellData>                           &cells;
      const std::vector<FaceData>                           &faces;
      const ContactTractionData                             &contact;
      std::map<types::boundary_id, const TractionFunction *> traction_on;
      const unsigned int                                     fe_degree;
      // Exact for the work of a degree p + 1 traction on monomials of the
      // local degree.
      const QGauss<1> edge_rule;
    };
  } // namespace equilibration
} // namespace coulomb_adapt

#endif
