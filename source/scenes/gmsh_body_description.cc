#include <deal.II/base/function.h>

#include <coulomb_adapt/scenes/gmsh_file.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

#include <set>

// What one body of a gmsh scene is made of: the boundary conditions and
// loads of its boundary ids (from the conditions of the physical groups on
// them), its point supports and its body force. All prescribed values and
// loads are scaled by the current load step's fraction when evaluated.
namespace coulomb_adapt
{
  namespace scenes
  {
    namespace
    {
      // The conditions of the groups that share one boundary id, combined
      // (the constructor checked that they agree).
      GmshFile::GroupConditions
      combined_conditions(
        const std::vector<std::string>                         &groups,
        const std::map<std::string, GmshFile::GroupConditions> &conditions)
      {
        GmshFile::GroupConditions combined;
        for (const auto &g : groups)
          {
            const GmshFile::GroupConditions &c = conditions.at(g);
            if (c.rotation)
              combined.rotation = c.rotation;
            for (unsigned int k = 0; k < 2; ++k)
              if (c.fixed[k])
                combined.fixed[k] = c.fixed[k];
            combined.traction += c.traction;
            combined.pressure += c.pressure;
            combined.shear += c.shear;
            combined.loaded = combined.loaded || c.loaded;
          }
        return combined;
      }



      // The Dirichlet data and the traction of boundary id @p id. The
      // functions read *load_fraction when they are evaluated.
      void
      add_boundary_conditions(const types::boundary_id         id,
                              const GmshFile::GroupConditions &c,
                              const Point<2>                  &centre,
                              const double                    *load_fraction,
                              BodyDescription                 &d)
      {
        // The linearised rigid rotation: the small-strain problem's rigid
        // motion (R(angle) x - x would strain the body by (cos(angle) - 1)
        // in the linearised strain).
        if (c.rotation)
          d.dirichlet.push_back(
            {id,
             ComponentMask(2, true),
             std::make_shared<FunctionFromFunctionObjects<2>>(
               std::vector<std::function<double(const Point<2> &)>>{
                 [load_fraction, centre, angle = *c.rotation](
                   const Point<2> &x) {
                   return -*load_fraction * angle * (x[1] - centre[1]);
                 },
                 [load_fraction, centre, angle = *c.rotation](
                   const Point<2> &x) {
                   return *load_fraction * angle * (x[0] - centre[0]);
                 }})});
        else if (c.fixed[0] || c.fixed[1])
          {
            const std::vector<bool>   mask   = {c.fixed[0].has_value(),
                                                c.fixed[1].has_value()};
            const std::vector<double> values = {c.fixed[0].value_or(0.),
                                                c.fixed[1].value_or(0.)};
            std::shared_ptr<const Function<2>> displacement;
            if (values[0] == 0 && values[1] == 0)
              displacement = std::make_shared<Functions::ZeroFunction<2>>(2);
            else
              displacement = std::make_shared<FunctionFromFunctionObjects<2>>(
                std::vector<std::function<double(const Point<2> &)>>{
                  [load_fraction, v = values[0]](const Point<2> &) {
                    return *load_fraction * v;
                  },
                  [load_fraction, v = values[1]](const Point<2> &) {
                    return *load_fraction * v;
                  }});
            d.dirichlet.push_back({id, ComponentMask(mask), displacement});
          }
        if (c.loaded)
          d.tractions.push_back(
            {id,
             [load_fraction,
              traction = c.traction,
              pressure = c.pressure,
              shear    = c.shear](const Point<2> &, const Tensor<1, 2> &n) {
               const Tensor<1, 2> t({-n[1], n[0]});
               return *load_fraction * (traction - pressure * n + shear * t);
             }});
      }
    } // namespace



    BodyDescription
    GmshFile::describe_body(const unsigned int body) const
    {
      BodyDescription d;
      d.name                = "body " + std::to_string(body + 1);
      d.material            = materials[body];
      d.contact_boundary_id = boundary_ids::contact;

      std::set<types::boundary_id> ids_of_body;
      for (const auto &line :
           geometry.meshes[body].boundary_lines.boundary_lines)
        ids_of_body.insert(line.boundary_id);
      for (const auto &[id, groups] : geometry.groups_of_boundary_id)
        if (ids_of_body.count(id) > 0)
          add_boundary_conditions(id,
                                  combined_conditions(groups, conditions),
                                  rotation_centre,
                                  &load_fraction,
                                  d);

      // Point supports select their vertex (refinement keeps it).
      double extent = 0;
      for (const auto &v : geometry.meshes[body].vertices)
        extent = std::max({extent, std::abs(v[0]), std::abs(v[1])});
      for (const auto &support : geometry.point_supports)
        if (support.body == body)
          {
            const auto    &fixed     = conditions.at(support.group).fixed;
            const Point<2> position  = support.position;
            const double   tolerance = 1e-12 * extent;
            d.point_constraints.push_back(
              {[position, tolerance](const Point<2> &x) {
                 return x.distance(position) <= tolerance;
               },
               ComponentMask(
                 std::vector<bool>{fixed[0].has_value(), fixed[1].has_value()}),
               std::nullopt});
            d.support_points.push_back(position);
          }

      const BodyForce &f = body_forces[body];
      if (f.density > 0 && (f.gravity.norm() > 0 || f.angular_velocity != 0))
        d.body_force = [this, f](const Point<2> &x) {
          return load_fraction * f.density *
                 (f.gravity +
                  f.angular_velocity * f.angular_velocity * (x - f.axis));
        };
      return d;
    }
  } // namespace scenes
} // namespace coulomb_adapt
