#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/scene.h>

namespace coulomb_adapt
{
  void
  declare_body_materials(ParameterHandler &prm,
                         const double      youngs_modulus_1,
                         const double      poissons_ratio_1,
                         const double      youngs_modulus_2,
                         const double      poissons_ratio_2)
  {
    prm.enter_subsection("Body 1");
    MaterialConstants::declare_parameters(prm,
                                          youngs_modulus_1,
                                          poissons_ratio_1);
    prm.leave_subsection();
    prm.enter_subsection("Body 2");
    MaterialConstants::declare_parameters(prm,
                                          youngs_modulus_2,
                                          poissons_ratio_2);
    prm.leave_subsection();
  }



  std::array<MaterialConstants, 2>
  parse_body_materials(ParameterHandler &prm, const std::string &path)
  {
    std::array<MaterialConstants, 2> materials;
    for (unsigned int b = 0; b < 2; ++b)
      {
        const std::string body = "Body " + std::to_string(b + 1);
        prm.enter_subsection(body);
        materials[b].parse_parameters(prm, path + "/" + body);
        prm.leave_subsection();
      }
    return materials;
  }



  void
  Scene::refine_initial_mesh(const unsigned int, Triangulation<2> &) const
  {}



  std::string
  Scene::mesh_source() const
  {
    return "";
  }



  std::map<std::string, double>
  Scene::reference_values() const
  {
    return {};
  }



  std::vector<std::string>
  Scene::load_entries() const
  {
    return {"the load entries of scene '" + name() + "'"};
  }



  unsigned int
  Scene::n_load_steps() const
  {
    return 1;
  }



  void
  Scene::set_load_step(const unsigned int) const
  {}



  double
  Scene::load_increment_ratio(const unsigned int) const
  {
    return 0;
  }



  std::unique_ptr<Scene>
  Scene::with_coarser_graded_meshes(const unsigned int) const
  {
    return nullptr;
  }



  bool
  Scene::coarser_meshes_scale_every_size() const
  {
    return false;
  }
} // namespace coulomb_adapt
