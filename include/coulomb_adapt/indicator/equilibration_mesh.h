#ifndef coulomb_adapt_indicator_equilibration_mesh_h
#define coulomb_adapt_indicator_equilibration_mesh_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * The pieces of the element equilibration technique
   * (equilibrated_stress_errors()): here the local mesh of a body seen by
   * the node systems; the node systems (equilibration_node_systems.h) and
   * the optimisation of their free parameters (traction_optimisation.h)
   * work on it.
   */
  namespace equilibration
  {
    // A cell of the local mesh (locally owned or ghost) with what the node
    // systems need from it.
    struct CellData
    {
      DoFHandler<2>::active_cell_iterator cell;
      bool                                owned;
      /** Per node k of the scalar base element: the global DoF index of its
       * x component (the node's name on every rank). */
      std::vector<types::global_dof_index> nodes;
      /** Per node k and component c: the global DoF index. */
      std::vector<std::array<types::global_dof_index, 2>> component_dofs;
      /** The nodes' positions. */
      std::vector<Point<2>> points;
      /** int_E sigma_c : eps(phi_k e_c) - f . phi_k e_c, [k][c]. */
      std::vector<std::array<double, 2>> residual;
      /** Local face index of each of the cell's faces. */
      std::vector<unsigned int> faces;
    };

    // A face of the local mesh. Its traction F is sigma^ n of the "plus"
    // cell (the smaller CellId), the other cell sees -F.
    struct FaceData
    {
      int          plus = -1, minus = -1;
      Point<2>     v0, v1;
      Tensor<1, 2> normal; // outward normal of the plus cell
      double       length      = 0;
      bool         at_boundary = false;
      /** Per component: the moments are unknown (interior and Dirichlet
       * edges) rather than prescribed data. */
      std::array<bool, 2> unknown = {{true, true}};
      /** The nodes on the face and their parameter s in [0, 1] along
       * v0 -> v1. */
      std::vector<types::global_dof_index> nodes;
      std::vector<double>                  s;
      /** The nodes' positions (on a curved face, off its chord). */
      std::vector<Point<2>> points;
      /** The nodes' DoF indices per component: the names of the free
       * parameters of their node systems. */
      std::vector<std::array<types::global_dof_index, 2>> node_dofs;
      /** Moments b[node][c], and those of the averaged FE traction. */
      std::vector<std::array<double, 2>> moments, average;
      /** The change of b[node][c] per unit of the free parameter of the
       * node system of (node, c) (0 where that system has none). */
      std::vector<std::array<double, 2>> kernel;
      /** Nodal coefficients of F (degree p, Lagrange in s), and the inverse
       * of the edge mass matrix that maps moments to them. */
      std::vector<std::array<double, 2>> coefficients;
      FullMatrix<double>                 mass_inverse;
      /** On a face of a held line (held_reactions.h), the moments and
       * nodal coefficients of the traction g that both its cells carry
       * besides eta F; empty elsewhere. */
      std::vector<std::array<double, 2>> held_moments, held_coefficients;
    };

    // The largest entry of the cells' element residuals: the scale of the
    // node systems' defects.
    inline double
    largest_cell_residual(const std::vector<CellData> &cells)
    {
      double largest = 0;
      for (const auto &cell : cells)
        for (const auto &r : cell.residual)
          largest = std::max({largest, std::abs(r[0]), std::abs(r[1])});
      return largest;
    }

    // Whether node @p k of @p face is one of its ends (a vertex), not a
    // node inside it.
    inline bool
    is_face_end(const FaceData &face, const unsigned int k)
    {
      return face.s[k] == 0 || face.s[k] == 1;
    }

    // Lagrange polynomials of the face's nodes at parameter s (p <= 2:
    // at most three nodes; a fixed array, as this is called per
    // quadrature point of every face).
    inline std::array<double, 3>
    face_shape_values(const std::vector<double> &nodes_s, const double s)
    {
      AssertIndexRange(nodes_s.size(), 4);
      std::array<double, 3> values = {{1., 1., 1.}};
      for (unsigned int k = 0; k < nodes_s.size(); ++k)
        for (unsigned int l = 0; l < nodes_s.size(); ++l)
          if (l != k)
            values[k] *= (s - nodes_s[l]) / (nodes_s[k] - nodes_s[l]);
      return values;
    }

    // Their derivatives d/ds at s (the face's tangent: face_geometry()).
    // deal.II's Polynomials::generate_complete_Lagrange_basis() gives the
    // same, but builds polynomial objects on the heap per call; this runs
    // per quadrature point of the loaded faces.
    inline std::array<double, 3>
    face_shape_derivatives(const std::vector<double> &nodes_s, const double s)
    {
      AssertIndexRange(nodes_s.size(), 4);
      std::array<double, 3> derivatives = {{0., 0., 0.}};
      for (unsigned int k = 0; k < nodes_s.size(); ++k)
        for (unsigned int m = 0; m < nodes_s.size(); ++m)
          if (m != k)
            {
              double term = 1. / (nodes_s[k] - nodes_s[m]);
              for (unsigned int l = 0; l < nodes_s.size(); ++l)
                if (l != k && l != m)
                  term *= (s - nodes_s[l]) / (nodes_s[k] - nodes_s[l]);
              derivatives[k] += term;
            }
      return derivatives;
    }

    // The point of @p face at parameter s: its nodes' positions
    // interpolated, as the isoparametric mapping places the face (on a
    // straight face, the point of the chord). The node systems balance
    // each cell against tractions at these points: the FE's shape
    // functions on the face sum the nodes' positions to them. A traction
    // put on the chord instead leaves every cell next to a curved face
    // with a load out of balance (on the press fit with torque, P2, whose
    // clamped circles are curved: a rigid-motion load of 2.4e-2 of the
    // load, and epsilon 3.4 % where zz and spr give 0.12 and 0.18 %).
    inline Point<2>
    face_point(const FaceData &face, const double s)
    {
      const auto phi = face_shape_values(face.s, s);
      Point<2>   x;
      for (unsigned int k = 0; k < face.points.size(); ++k)
        x += phi[k] * face.points[k];
      return x;
    }

    // A face at parameter s as the FE sees it: the point, the outward
    // normal of the plus cell, and |dx/ds|, the length element of the FE's
    // face quadrature. A prescribed traction is integrated with these, as
    // the FE load vector is: on a curved face the chord's normal and
    // length put a node system out of balance with the cell's residual
    // (P2 press fit, a tangential traction on the curved bore: node
    // systems' defect 9.0e-4).
    struct FacePointGeometry
    {
      Point<2>     point;
      Tensor<1, 2> normal;
      double       length_element;
    };

    inline FacePointGeometry
    face_geometry(const FaceData &face, const double s)
    {
      const auto   derivatives = face_shape_derivatives(face.s, s);
      Tensor<1, 2> tangent;
      for (unsigned int k = 0; k < face.points.size(); ++k)
        tangent += derivatives[k] * face.points[k];
      FacePointGeometry g;
      g.point          = face_point(face, s);
      g.length_element = tangent.norm();
      g.normal[0]      = tangent[1] / g.length_element;
      g.normal[1]      = -tangent[0] / g.length_element;
      if (g.normal * face.normal < 0)
        g.normal *= -1;
      return g;
    }

    // The Legendre polynomial of degree n on [0, 1] at s.
    inline double
    edge_bubble(const unsigned int n, const double s)
    {
      const double x        = 2 * s - 1;
      double       previous = 1, current = x;
      if (n == 0)
        return 1;
      for (unsigned int k = 1; k < n; ++k)
        {
          const double next =
            ((2 * k + 1) * x * current - k * previous) / (k + 1);
          previous = current;
          current  = next;
        }
      return current;
    }

    inline double
    face_parameter(const FaceData &face, const Point<2> &x)
    {
      const Tensor<1, 2> d = face.v1 - face.v0;
      return (x - face.v0) * d / d.norm_square();
    }
  } // namespace equilibration
} // namespace coulomb_adapt

#endif
