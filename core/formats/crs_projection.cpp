// PROJ behind crs_projection.hpp: every PROJ object is owned by a small RAII handle and every
// call uses its own context, so imports on several threads never share PROJ state.
#include "core/formats/crs_projection.hpp"

#include <proj.h>

#include <cmath>
#include <memory>
#include <sstream>

#include "core/errors.hpp"

namespace cullcheck::formats {
namespace {

struct ContextDeleter {
  void operator()(PJ_CONTEXT* c) const { proj_context_destroy(c); }
};
struct PjDeleter {
  void operator()(PJ* p) const { proj_destroy(p); }
};
using Context = std::unique_ptr<PJ_CONTEXT, ContextDeleter>;
using Pj = std::unique_ptr<PJ, PjDeleter>;

Context new_context() {
  Context ctx(proj_context_create());
  proj_log_level(ctx.get(), PJ_LOG_NONE);  // errors reach the user as InputErrors, not on stderr
  return ctx;
}

std::string last_error(PJ_CONTEXT* ctx) {
  const char* text = proj_context_errno_string(ctx, proj_context_errno(ctx));
  return text ? text : "unknown PROJ error";
}

bool is_geographic(PJ_TYPE t) {
  return t == PJ_TYPE_GEOGRAPHIC_CRS || t == PJ_TYPE_GEOGRAPHIC_2D_CRS || t == PJ_TYPE_GEOGRAPHIC_3D_CRS;
}

}  // namespace

CrsKind describe_crs(const std::string& crs, const std::string& where) {
  const Context ctx = new_context();
  const Pj pj(proj_create(ctx.get(), crs.c_str()));
  if (!pj) throw InputError(where, "crs", "'" + crs + "' is not a coordinate reference system PROJ knows (" + last_error(ctx.get()) + ")");
  CrsKind kind;
  const char* name = proj_get_name(pj.get());
  kind.name = name ? name : crs;
  // A compound CRS (a plan CRS with a vertical one, as CityJSON's EPSG:7415 = RD New + NAP
  // height): its plan part decides, heights are taken in metres as the file gives them.
  const Pj horizontal(proj_get_type(pj.get()) == PJ_TYPE_COMPOUND_CRS ? proj_crs_get_sub_crs(ctx.get(), pj.get(), 0) : nullptr);
  const PJ* plan_crs = horizontal ? horizontal.get() : pj.get();
  const PJ_TYPE type = proj_get_type(plan_crs);
  if (is_geographic(type)) {
    kind.geographic = true;
    return kind;
  }
  if (type != PJ_TYPE_PROJECTED_CRS)
    throw InputError(where, "crs", "'" + crs + "' (" + kind.name + ") is neither projected nor geographic; footprints need a plan CRS");
  const Pj cs(proj_crs_get_coordinate_system(ctx.get(), plan_crs));
  double factor = 0.0;
  const char* unit = nullptr;
  if (!cs || proj_cs_get_axis_count(ctx.get(), cs.get()) < 2 ||
      !proj_cs_get_axis_info(ctx.get(), cs.get(), 0, nullptr, nullptr, nullptr, &factor, &unit, nullptr, nullptr) ||
      !(factor > 0.0) || !std::isfinite(factor))
    throw InputError(where, "crs", "'" + crs + "' (" + kind.name + ") has no linear unit PROJ can read");
  kind.metres_per_unit = factor;
  return kind;
}

namespace {

// Geographic CRS `crs` (longitude first) <-> the transverse Mercator centred at (lon0, lat0).
void transform_local(const std::string& crs, double lon0, double lat0, std::vector<Vec2>& points, const std::string& where,
                     PJ_DIRECTION direction) {
  if (!(std::abs(lat0) < 89.0) || !(std::abs(lon0) <= 180.0))
    throw InputError(where, "coordinates", "the data's centre (" + std::to_string(lon0) + ", " + std::to_string(lat0) +
                                               ") is no longitude/latitude a local projection can be centred on");
  const Context ctx = new_context();
  std::ostringstream target;
  target.precision(17);
  target << "+proj=tmerc +lat_0=" << lat0 << " +lon_0=" << lon0 << " +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +units=m +type=crs";
  const Pj raw(proj_create_crs_to_crs(ctx.get(), crs.c_str(), target.str().c_str(), nullptr));
  if (!raw) throw InputError(where, "crs", "no transformation from '" + crs + "' to local metres (" + last_error(ctx.get()) + ")");
  // Longitude first, as GeoJSON (and most files) write it, whatever the CRS's axis order.
  const Pj op(proj_normalize_for_visualization(ctx.get(), raw.get()));
  if (!op) throw InputError(where, "crs", "cannot take '" + crs + "' longitude first (" + last_error(ctx.get()) + ")");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const PJ_COORD out = proj_trans(op.get(), direction, proj_coord(points[i].x, points[i].y, 0, 0));
    if (!std::isfinite(out.xy.x) || !std::isfinite(out.xy.y)) {
      std::ostringstream p;
      p.precision(12);
      p << "point (" << points[i].x << ", " << points[i].y << ") cannot be projected " << (direction == PJ_FWD ? "to" : "from")
        << " local metres";
      throw InputError(where, "coordinates", p.str());
    }
    points[i] = {out.xy.x, out.xy.y};
  }
}

}  // namespace

void project_to_local_metres(const std::string& crs, double lon0, double lat0, std::vector<Vec2>& points,
                             const std::string& where) {
  transform_local(crs, lon0, lat0, points, where, PJ_FWD);
}

void local_metres_to_geographic(const std::string& crs, double lon0, double lat0, std::vector<Vec2>& points,
                                const std::string& where) {
  transform_local(crs, lon0, lat0, points, where, PJ_INV);
}

}  // namespace cullcheck::formats
