#include "cell_picture.hpp"

#include <fmt/format.h>

namespace uhpc::micro {

std::string cell_svg(const CellGeometry& cell, const CellDiscretization* mesh, const PictureOptions& o) {
  const double margin = 20.0, caption_height = o.caption.empty() ? 0.0 : 30.0;
  const double scale = (o.size_px - 2.0 * margin) / cell.side_m;
  // SVG's y axis points down: flip so that the picture shows the cell with y up.
  auto X = [&](double x) { return margin + x * scale; };
  auto Y = [&](double y) { return margin + (cell.side_m - y) * scale; };
  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\">\n"
      "<rect x=\"0\" y=\"0\" width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n"
      "<rect x=\"{2}\" y=\"{2}\" width=\"{3:.3f}\" height=\"{3:.3f}\" fill=\"#d9d4c7\" stroke=\"black\" stroke-width=\"1.5\"/>\n",
      o.size_px, static_cast<int>(o.size_px + caption_height), margin, cell.side_m * scale);
  if (mesh && o.show_mesh) {
    s += "<g fill=\"none\" stroke=\"#7a7466\" stroke-width=\"0.3\">\n";
    for (const auto& t : mesh->triangles) {
      const auto &a = mesh->nodes_m[t[0]], &b = mesh->nodes_m[t[1]], &c = mesh->nodes_m[t[2]];
      s += fmt::format("<path d=\"M{:.2f} {:.2f}L{:.2f} {:.2f}L{:.2f} {:.2f}Z\"/>\n", X(a[0]), Y(a[1]), X(b[0]), Y(b[1]),
                       X(c[0]), Y(c[1]));
    }
    s += "</g>\n<g fill=\"#2b2b2b\">\n";
    for (const auto& n : mesh->nodes_m) s += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"0.8\"/>\n", X(n[0]), Y(n[1]));
    s += "</g>\n";
  }
  s += "<g fill=\"#1f4e79\" fill-opacity=\"0.85\" stroke=\"#0b2540\" stroke-width=\"0.8\">\n";
  for (const Pore& p : cell.pores)
    s += fmt::format("<circle cx=\"{:.3f}\" cy=\"{:.3f}\" r=\"{:.3f}\"/>\n", X(p.center_m.x), Y(p.center_m.y),
                     p.radius_m() * scale);
  s += "</g>\n<g stroke=\"#d62728\" stroke-width=\"2\" stroke-linecap=\"round\">\n";
  for (const CrackSeed& c : cell.seeds)
    s += fmt::format("<line x1=\"{:.3f}\" y1=\"{:.3f}\" x2=\"{:.3f}\" y2=\"{:.3f}\"/>\n", X(c.root_m.x), Y(c.root_m.y),
                     X(c.tip_m.x), Y(c.tip_m.y));
  s += "</g>\n";
  if (!o.caption.empty())
    s += fmt::format("<text x=\"{}\" y=\"{:.1f}\" font-family=\"sans-serif\" font-size=\"15\">{}</text>\n", margin,
                     o.size_px + caption_height - 12.0, o.caption);
  s += "</svg>\n";
  return s;
}

}  // namespace uhpc::micro
