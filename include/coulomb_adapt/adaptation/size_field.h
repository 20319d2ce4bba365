#ifndef coulomb_adapt_adaptation_size_field_h
#define coulomb_adapt_adaptation_size_field_h

#include <deal.II/base/point.h>

#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>

#include <array>
#include <vector>

namespace coulomb_adapt
{
  /** A triangle of the current mesh with the target element size h* at
   * its vertices: a piece of the size field handed to gmsh. */
  struct SizeFieldTriangle
  {
    std::array<Point<2>, 3> vertices;
    std::array<double, 3>   size;
  };

  /**
   * The size field h*(x) of a triangle mesh, on rank @p root of the body's
   * communicator (empty on the others, which do not mesh this body; the
   * field does not depend on which rank gathers it): h*_E = r_E h_E
   * with h_E = (4 |E| / sqrt 3)^1/2, the edge of the equilateral triangle of
   * the same area (so that the cell count of the new mesh is sum_E r_E^-2
   * for any shape), smoothed by taking at each vertex the geometric mean of
   * h*_E over the cells around it, then scaled so that the smoothed,
   * piecewise linear field has the cell count sum_E r_E^-2 of the
   * unsmoothed one. @p ratio holds r_E per active cell (locally owned
   * entries).
   */
  std::vector<SizeFieldTriangle>
  nodal_size_field(const ElasticBody    &body,
                   const Vector<double> &ratio,
                   const unsigned int    root = 0);
} // namespace coulomb_adapt

#endif
