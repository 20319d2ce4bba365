#include <deal.II/lac/vector.h>

#include <coulomb_adapt/scenes/scaled_scene.h>

namespace coulomb_adapt
{
  namespace
  {
    // A function of the scene divided by the load scale, at every point
    // and for every derivative the program asks for.
    class ScaledFunction : public Function<2>
    {
    public:
      ScaledFunction(std::shared_ptr<const Function<2>> function,
                     std::shared_ptr<const double>      scale)
        : Function<2>(function->n_components)
        , function(std::move(function))
        , scale(std::move(scale))
      {}

      double
      value(const Point<2> &p, const unsigned int component) const override
      {
        return function->value(p, component) / *scale;
      }

      void
      vector_value(const Point<2> &p, Vector<double> &values) const override
      {
        function->vector_value(p, values);
        values /= *scale;
      }

      Tensor<1, 2>
      gradient(const Point<2> &p, const unsigned int component) const override
      {
        return function->gradient(p, component) / *scale;
      }

      void
      vector_gradient(const Point<2>            &p,
                      std::vector<Tensor<1, 2>> &gradients) const override
      {
        function->vector_gradient(p, gradients);
        for (auto &g : gradients)
          g /= *scale;
      }

    private:
      const std::shared_ptr<const Function<2>> function;
      const std::shared_ptr<const double>      scale;
    };
  } // namespace



  ScaledScene::ScaledScene(std::unique_ptr<Scene> scene)
    : scene(std::move(scene))
    , scale(std::make_shared<double>(1.))
    , displacement_scale(std::make_shared<double>(1.))
  {}



  ScaledScene::ScaledScene(std::unique_ptr<Scene>  scene,
                           std::shared_ptr<double> load_scale,
                           std::shared_ptr<double> displacement_scale)
    : scene(std::move(scene))
    , scale(std::move(load_scale))
    , displacement_scale(std::move(displacement_scale))
  {}



  void
  ScaledScene::set_load_scale(const double load_scale)
  {
    *scale              = load_scale;
    *displacement_scale = load_scale;
  }



  void
  ScaledScene::set_scales(const units::Scales &scales)
  {
    *scale              = scales.stress;
    *displacement_scale = scales.displacement;
  }



  units::Scales
  ScaledScene::scales() const
  {
    units::Scales s;
    s.stress       = *scale;
    s.displacement = *displacement_scale;
    return s;
  }



  double
  ScaledScene::load_scale() const
  {
    return *scale;
  }



  std::string
  ScaledScene::name() const
  {
    return scene->name();
  }



  void
  ScaledScene::create_coarse_mesh(const unsigned int body,
                                  const CellType     cell_type,
                                  Triangulation<2>  &tria) const
  {
    scene->create_coarse_mesh(body, cell_type, tria);
  }



  void
  ScaledScene::refine_initial_mesh(const unsigned int body,
                                   Triangulation<2>  &tria) const
  {
    scene->refine_initial_mesh(body, tria);
  }



  BodyDescription
  ScaledScene::describe_body(const unsigned int body) const
  {
    BodyDescription                     d = scene->describe_body(body);
    const std::shared_ptr<const double> s = scale;
    for (auto &t : d.tractions)
      t.traction = [traction = t.traction, s](const Point<2>     &x,
                                              const Tensor<1, 2> &n) {
        return traction(x, n) / *s;
      };
    if (d.body_force)
      d.body_force = [body_force = d.body_force, s](const Point<2> &x) {
        return body_force(x) / *s;
      };
    const std::shared_ptr<const double> D = displacement_scale;
    for (auto &dirichlet : d.dirichlet)
      dirichlet.displacement =
        std::make_shared<ScaledFunction>(dirichlet.displacement, D);
    if (d.exact_displacement)
      d.exact_displacement =
        std::make_shared<ScaledFunction>(d.exact_displacement, D);
    // The material is a value: the bodies are made again after a change
    // of P / D. Dividing by 1 keeps the modulus to the last bit.
    d.material.youngs_modulus /= *scale / *displacement_scale;
    return d;
  }



  std::string
  ScaledScene::mesh_source() const
  {
    return scene->mesh_source();
  }



  std::map<std::string, double>
  ScaledScene::reference_values() const
  {
    return scene->reference_values();
  }



  std::vector<std::string>
  ScaledScene::load_entries() const
  {
    return scene->load_entries();
  }



  unsigned int
  ScaledScene::n_load_steps() const
  {
    return scene->n_load_steps();
  }



  void
  ScaledScene::set_load_step(const unsigned int step) const
  {
    scene->set_load_step(step);
  }



  double
  ScaledScene::load_increment_ratio(const unsigned int step) const
  {
    return scene->load_increment_ratio(step);
  }



  bool
  ScaledScene::coarser_meshes_scale_every_size() const
  {
    return scene->coarser_meshes_scale_every_size();
  }



  std::unique_ptr<Scene>
  ScaledScene::with_coarser_graded_meshes(const unsigned int k) const
  {
    std::unique_ptr<Scene> coarser = scene->with_coarser_graded_meshes(k);
    if (!coarser)
      return nullptr;
    return std::unique_ptr<Scene>(
      new ScaledScene(std::move(coarser), scale, displacement_scale));
  }
} // namespace coulomb_adapt
