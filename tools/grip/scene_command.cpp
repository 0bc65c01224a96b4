// `grip scene NAME [--image FILE]`: describes and draws a built-in scene.

#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "grip/scenes/scenes.hpp"
#include "render.hpp"

namespace grip::tools {

namespace {
struct SceneOptions {
  std::string name;
  std::string image;
};

int run_scene(const SceneOptions& o) {
  auto scene = make_scene(o.name);
  if (!scene) {
    std::cerr << "grip scene: " << scene.error().message << "\n";
    return 2;
  }
  std::cout << scene->name << ": " << scene->description << "\n"
            << "  size " << scene->grid.width_m() << " m x " << scene->grid.height_m() << " m ("
            << scene->grid.width() << " x " << scene->grid.height() << " cells of "
            << scene->grid.resolution() << " m)\n"
            << "  start (" << scene->start_x_m << ", " << scene->start_y_m << ") heading "
            << scene->start_theta_rad << " rad, goal (" << scene->goal_x_m << ", "
            << scene->goal_y_m << ") radius " << scene->goal_radius_m << " m\n";
  if (o.image.empty()) return 0;
  auto canvas = MapCanvas::create(scene->grid, 3);
  if (!canvas) {
    std::cerr << "grip scene: " << canvas.error().message << "\n";
    return 1;
  }
  canvas->draw_grid(scene->grid);
  canvas->draw_disk({scene->goal_x_m, scene->goal_y_m}, scene->goal_radius_m, 0.1, 0.7, 0.2, 0.5);
  canvas->draw_marker({scene->start_x_m, scene->start_y_m}, 6.0, 0.95, 0.6, 0.0);
  canvas->draw_label(scene->name, 10.0, 24.0, 16.0);
  if (auto s = canvas->write_png(o.image); !s) {
    std::cerr << "grip scene: " << s.error().message << "\n";
    return 1;
  }
  std::cout << "  drawn to " << o.image << "\n";
  return 0;
}
}  // namespace

void register_scene_command(CLI::App& app) {
  auto options = std::make_shared<SceneOptions>();
  CLI::App* cmd = app.add_subcommand("scene", "Describe and draw a built-in scene");
  cmd->add_option("name", options->name, "meandros, labyrinth or rooms")->required();
  cmd->add_option("--image", options->image, "Write a PNG of the scene");
  cmd->callback([options]() {
    if (const int rc = run_scene(*options); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
