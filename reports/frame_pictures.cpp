#include "reports/frame_pictures.hpp"

#include <algorithm>
#include <iterator>

#include "reports/pictures.hpp"

namespace cullcheck {

FramePictures write_frame_pictures(const Scene& scene, const Camera& camera, const std::vector<ObjectId>& pvs,
                                   const oracle::OracleOptions& options, const std::string& dir, const std::string& stem,
                                   int map_size_px) {
  FramePictures out;
  const oracle::Oracle truth(scene);
  const oracle::OracleAnswer answer = truth.visible_set(camera, options);
  std::vector<ObjectId> sorted_pvs = pvs;
  std::sort(sorted_pvs.begin(), sorted_pvs.end());
  const oracle::PixelComparison pixels = truth.pixels().compare(camera, sorted_pvs, options.sampling.threads);
  out.seen = answer.visible;
  std::vector<oracle::WitnessRay> rays;
  for (const auto& [id, ray] : pixels.witnesses) out.seen.push_back(id);
  std::sort(out.seen.begin(), out.seen.end());
  out.seen.erase(std::unique(out.seen.begin(), out.seen.end()), out.seen.end());
  std::set_difference(out.seen.begin(), out.seen.end(), sorted_pvs.begin(), sorted_pvs.end(), std::back_inserter(out.missed));
  for (ObjectId id : out.missed) {
    if (answer.sampling && answer.sampling->witnesses.count(id)) rays.push_back(answer.sampling->witnesses.at(id));
    else if (pixels.witnesses.count(id)) rays.push_back(pixels.witnesses.at(id));
  }
  out.misdrawn_pixels = pixels.misdrawn_pixels;
  out.map = dir + "/" + stem + "map.png";
  out.image = dir + "/" + stem + "frame.png";
  write_png(top_down_map(scene, camera, sorted_pvs, out.seen, out.missed, rays, map_size_px), out.map);
  write_png(frame_image(truth.pixels().render(camera, nullptr, options.sampling.threads), pixels), out.image);
  return out;
}

}  // namespace cullcheck
