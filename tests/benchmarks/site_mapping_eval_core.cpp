#include "site_mapping_eval_core.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "hylo/registration/voxel_filter.h"
#include "hylo/sim/surface_distance.h"
#include "hylo/sim/terrain.h"
#include "hylo/sim_io/reference_outputs.h"

namespace hylo::site_eval {
namespace {

using Clock = std::chrono::steady_clock;
double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

PointCloud ToFloat(const std::vector<Eigen::Vector3d>& points) {
  PointCloud out;
  out.reserve(points.size());
  for (const Eigen::Vector3d& p : points) out.push_back(p.cast<float>());
  return out;
}

// True for a primitive thinner than 0.1 m across (a cable, a lattice beam, a busbar): a
// surface of a few centimetres that an MLS fit over several centimetres cannot follow.
bool IsThin(const sim::Primitive& p) {
  return p.shape == sim::Primitive::Shape::kCylinder ? 2.0 * p.radius_m < 0.1
                                                     : 2.0 * p.half_extent_m.minCoeff() < 0.1;
}

// RMS and tail of the distances of `points` (every `stride`-th) to the true surfaces.
Thickness MeasureThickness(const sim::SurfaceDistanceField& field,
                           const std::vector<sim::Primitive>& primitives,
                           const std::vector<Eigen::Vector3d>& points, std::size_t max_samples) {
  Thickness t;
  const std::size_t stride =
      max_samples == 0 ? 1 : std::max<std::size_t>(1, points.size() / max_samples);
  std::vector<double> distances;
  double sum_sq = 0, sum_sq_ground = 0, sum_sq_object = 0, sum_sq_thin = 0, sum_sq_box = 0;
  std::size_t ground = 0, thin = 0, box = 0;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    const sim::SurfaceDistance d = field.Nearest(points[i]);
    const double d2 = d.distance_m * d.distance_m;
    sum_sq += d2;
    (d.IsGround() ? sum_sq_ground : sum_sq_object) += d2;
    ground += d.IsGround();
    if (!d.IsGround() && IsThin(primitives[d.primitive])) {
      sum_sq_thin += d2;
      ++thin;
    } else if (!d.IsGround() && primitives[d.primitive].shape == sim::Primitive::Shape::kBox) {
      sum_sq_box += d2;
      ++box;
    }
    distances.push_back(d.distance_m);
  }
  t.points = distances.size();
  if (t.points == 0) return t;
  const std::size_t objects = t.points - ground;
  t.rms_m = std::sqrt(sum_sq / t.points);
  t.rms_ground_m = ground ? std::sqrt(sum_sq_ground / ground) : 0.0;
  t.rms_object_m = objects ? std::sqrt(sum_sq_object / objects) : 0.0;
  t.rms_thin_m = thin ? std::sqrt(sum_sq_thin / thin) : 0.0;
  t.fraction_thin = double(thin) / t.points;
  t.rms_thick_box_m = box ? std::sqrt(sum_sq_box / box) : 0.0;
  const std::size_t cylinders = objects - thin - box;
  t.rms_thick_cylinder_m =
      cylinders ? std::sqrt((sum_sq_object - sum_sq_thin - sum_sq_box) / cylinders) : 0.0;
  t.fraction_ground = double(ground) / t.points;
  t.beyond_10cm = double(std::count_if(distances.begin(), distances.end(),
                                       [](double d) { return d > 0.1; })) / t.points;
  const std::size_t k95 = static_cast<std::size_t>(0.95 * (t.points - 1));
  std::nth_element(distances.begin(), distances.begin() + k95, distances.end());
  t.p95_m = distances[k95];
  return t;
}

// A map of about `count` points with the density of the full map: whole scans spread evenly
// over the session, cut to `count`.
std::vector<Eigen::Vector3d> TimingMap(const AccumulatedMap& map, std::size_t count) {
  const std::size_t scans = map.scan_begin.size();
  if (scans == 0 || map.points_map.size() <= count) return map.points_map;
  const std::size_t per_scan = map.points_map.size() / scans;
  const std::size_t wanted_scans = std::min(scans, count / std::max<std::size_t>(1, per_scan) + 1);
  std::vector<Eigen::Vector3d> out;
  out.reserve(count);
  for (std::size_t k = 0; k < wanted_scans && out.size() < count; ++k) {
    const std::size_t s = k * scans / wanted_scans;
    const std::size_t end = s + 1 < scans ? map.scan_begin[s + 1] : map.points_map.size();
    for (std::size_t i = map.scan_begin[s]; i < end && out.size() < count; ++i) {
      out.push_back(map.points_map[i]);
    }
  }
  return out;
}

double CraftSeconds(const std::vector<Eigen::Vector3d>& points, terrain::CraftOptions options,
                    int threads) {
  options.num_threads = threads;
  const terrain::CraftResult r = terrain::CraftMap(points, options);
  return r.sampling_seconds + r.mls_seconds;
}

CraftFigures MeasureCrafting(const SiteEvalOptions& options, const AccumulatedMap& map,
                             const sim::SurfaceDistanceField& field,
                             const std::vector<sim::Primitive>& primitives) {
  CraftFigures f;
  f.raw = MeasureThickness(field, primitives, map.points_map, options.thickness_samples);
  std::vector<Eigen::Vector3d> sampled;
  for (std::size_t i : registration::UniformSampleIndices(
           ToFloat(map.points_map), static_cast<float>(options.craft.voxel_size_m))) {
    sampled.push_back(map.points_map[i]);
  }
  f.sampled = MeasureThickness(field, primitives, sampled, options.thickness_samples);
  const auto start = Clock::now();
  const terrain::CraftResult crafted = terrain::CraftMap(map.points_map, options.craft);
  f.seconds = SecondsSince(start);
  f.crafted_points = crafted.points_world.size();
  f.sampled_points = crafted.num_sampled;
  f.support_points = crafted.num_support;
  f.small_scale_points = crafted.num_small_scale;
  f.crafted = MeasureThickness(field, primitives, crafted.points_world, options.thickness_samples);
  if (options.timing_points > 0) {
    const std::vector<Eigen::Vector3d> timing = TimingMap(map, options.timing_points);
    f.timing_points = timing.size();
    f.seconds_1_thread = CraftSeconds(timing, options.craft, 1);
    f.seconds_2_threads = CraftSeconds(timing, options.craft, 2);
  }
  return f;
}

// Cells of the 8-neighbourhood without ground points (outside the grid counts as none).
int EmptyNeighbours(const terrain::GridMap& grid, std::size_t cell) {
  const terrain::GridGeometry& g = grid.geometry();
  const std::vector<float>& count = grid.Layer(terrain::layers::kPointCount);
  int empty = 0;
  for (int dr = -1; dr <= 1; ++dr) {
    for (int dc = -1; dc <= 1; ++dc) {
      const int col = g.Col(cell) + dc, row = g.Row(cell) + dr;
      empty += !g.Contains(col, row) || count[g.Index(col, row)] == 0.f;
    }
  }
  return empty;
}

// One row per cell with ground points or a slope: where the error sits, for analysis.
void WriteCellTable(const std::string& path, const terrain::TraversabilityMap& map,
                    const evaluation::TruthField& truth, const evaluation::TruthField& footprint) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
  const terrain::GridMap& grid = map.grid;
  const terrain::GridGeometry& g = grid.geometry();
  namespace L = terrain::layers;
  out << "col,row,x,y,points,filled,elevation,slope,roughness,step,class,truth,footprint_truth,"
         "empty_neighbours\n";
  for (std::size_t c = 0; c < g.NumCells(); ++c) {
    const float count = grid.Layer(L::kPointCount)[c];
    const float slope = grid.Layer(L::kSlope)[c];
    if (count == 0.f && std::isnan(slope)) continue;
    const Eigen::Vector2d xy = g.CentreWorld(g.Col(c), g.Row(c));
    out << g.Col(c) << ',' << g.Row(c) << ',' << xy.x() << ',' << xy.y() << ',' << count << ','
        << grid.Layer(L::kFilled)[c] << ',' << grid.Layer(L::kElevation)[c] << ',' << slope << ','
        << grid.Layer(L::kRoughness)[c] << ',' << grid.Layer(L::kStep)[c] << ','
        << static_cast<int>(map.classes[c]) << ',' << truth(xy.x(), xy.y()) << ','
        << footprint(xy.x(), xy.y()) << ',' << EmptyNeighbours(grid, c) << '\n';
  }
}

SlopeFigures MeasureSlope(const SiteEvalOptions& options, const evaluation::TruthField& truth,
                          const evaluation::TruthField& footprint_truth,
                          const std::vector<Eigen::Vector3d>& ground,
                          const std::vector<Eigen::Vector3d>& objects, const char* name,
                          bool estimate_edge_cells = false) {
  SlopeFigures f;
  terrain::TraversabilityOptions traversability = options.traversability;
  if (estimate_edge_cells) traversability.surface.unknown_at_data_edge = false;
  const auto start = Clock::now();
  const terrain::TraversabilityMap map =
      terrain::ComputeTraversability(ground, objects, traversability);
  f.seconds = SecondsSince(start);
  f.measured_cells = map.summary.elevation.measured_cells;
  f.cells_at_data_edge = map.summary.surface.cells_at_data_edge;
  f.cells_finer_scale = map.summary.surface.cells_finer_scale;
  f.noise_m = map.summary.surface.noise_m;
  f.slope = evaluation::CompareSlope(map.grid, truth);
  f.steep = evaluation::CheckSteepCells(map.grid, map.classes, truth,
                                        options.traversability.cost.max_slope_deg);
  f.slope_footprint = evaluation::CompareSlope(map.grid, footprint_truth);
  f.steep_footprint = evaluation::CheckSteepCells(map.grid, map.classes, footprint_truth,
                                                  options.traversability.cost.max_slope_deg);
  if (options.write_cell_tables) {
    WriteCellTable(options.out_dir + "/cells_" + name + ".csv", map, truth, footprint_truth);
  }
  return f;
}

}  // namespace

bool SiteEvalOptions::IsValid(std::string* why) const {
  std::string sub;
  std::ostringstream os;
  if (!sim.IsValid(&sub))
    os << "sim." << sub;
  else if (scan_stride < 1)
    os << "scan_stride = " << scan_stride << " must be >= 1";
  else if (!craft.IsValid(&sub))
    os << "craft: " << sub;
  else if (!(ground_voxel_m >= 0.0))
    os << "ground_voxel_m = " << ground_voxel_m << " must be >= 0";
  else if (!ground.IsValid(&sub))
    os << "ground: " << sub;
  else if (!traversability.IsValid(&sub))
    os << "traversability: " << sub;
  else if (out_dir.empty())
    os << "out_dir must name a directory";
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

SiteEvalOptions QuickOptions(const std::string& out_dir) {
  SiteEvalOptions options;
  options.sim = sim::SimulationOptions::Fast(20.0);
  options.timing_points = 200'000;
  options.out_dir = out_dir;
  return options;
}

double GroundFigures::TypeI() const {
  const double ground = double(ground_as_ground + ground_as_object);
  return ground > 0 ? ground_as_object / ground : 0.0;
}
double GroundFigures::TypeII() const {
  const double objects = double(object_as_ground + object_as_object);
  return objects > 0 ? object_as_ground / objects : 0.0;
}
double GroundFigures::Total() const {
  const double n = double(ground_as_ground + ground_as_object + object_as_ground + object_as_object);
  return n > 0 ? (ground_as_object + object_as_ground) / n : 0.0;
}
double GroundFigures::Kappa() const {
  // Cohen's kappa: agreement beyond what the two marginal ground fractions give by chance.
  const double n = double(ground_as_ground + ground_as_object + object_as_ground + object_as_object);
  if (n == 0) return 0.0;
  const double observed = (ground_as_ground + object_as_object) / n;
  const double truth_ground = double(ground_as_ground + ground_as_object) / n;
  const double said_ground = double(ground_as_ground + object_as_ground) / n;
  const double chance = truth_ground * said_ground + (1 - truth_ground) * (1 - said_ground);
  return chance < 1.0 ? (observed - chance) / (1.0 - chance) : 1.0;
}

AccumulatedMap AccumulateSessionA(const sim::SimulationOptions& options, const sim::Site& site,
                                  int scan_stride) {
  const auto start = Clock::now();
  const sim::SessionSimulator session(options, site, sim::SessionId::kA);
  const sim::LidarSimulator& lidar = session.lidar();
  const int64_t scans = session.trajectory().duration_ns() / lidar.period_ns();
  AccumulatedMap map;
  std::vector<sim::ReturnTruth> truth;
  for (int64_t index = 0; index < scans; index += scan_stride) {
    const LidarScan scan = lidar.Scan(static_cast<int>(index), session.start_ns(), &truth);
    // The stamp carries the lidar clock offset; the true firing time does not.
    const int64_t scan_true_ns = scan.t_ns - options.lidar.time_offset_ns - session.start_ns();
    map.scan_begin.push_back(map.points_map.size());
    for (std::size_t k = 0; k < scan.points.size(); ++k) {
      const ScanPoint& p = scan.points[k];
      const Eigen::Isometry3d T_map_lidar =
          session.trajectory().PoseAt(scan_true_ns + p.offset_ns) * options.lidar.T_imu_lidar;
      map.points_map.push_back(T_map_lidar * p.position_lidar.cast<double>());
      map.is_ground.push_back(truth[k].primitive < 0 ? 1 : 0);
    }
  }
  map.simulate_seconds = SecondsSince(start);
  return map;
}

evaluation::TruthField FootprintSlope(const sim::Site& site, double radius_m) {
  std::vector<Eigen::Vector2d> offsets;
  const double step_m = 0.1;
  const int k = static_cast<int>(std::floor(radius_m / step_m));
  for (int i = -k; i <= k; ++i) {
    for (int j = -k; j <= k; ++j) {
      if (std::hypot(i, j) * step_m > radius_m + 1e-9) continue;
      offsets.emplace_back(i * step_m, j * step_m);
    }
  }
  // The lattice is symmetric about the centre, so the plane's gradient decouples:
  // b = sum(x z) / sum(x^2), c = sum(y z) / sum(y^2), and sum(y^2) = sum(x^2).
  double sum_xx = 0.0;
  for (const Eigen::Vector2d& o : offsets) sum_xx += o.x() * o.x();
  const std::shared_ptr<const sim::Terrain> terrain = site.terrain;
  return [terrain, offsets, sum_xx](double x, double y) {
    if (sum_xx <= 0.0) return std::nan("");
    Eigen::Vector2d sum_xz = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& o : offsets) {
      sum_xz += o * terrain->CleanHeight(x + o.x(), y + o.y());
    }
    return std::atan(sum_xz.norm() / sum_xx) * 180.0 / M_PI;
  };
}

evaluation::TruthField ReadSimSlopeGrid(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read slope grid '" + path + "'");
  double x0 = 0, y0 = 0, resolution = 0;
  int cols = -1, rows = -1;
  std::string line;
  while ((cols < 0 || rows < 0 || resolution <= 0) && std::getline(in, line)) {
    std::istringstream ls(line);
    std::string key;
    if (!(ls >> key) || key[0] == '#') continue;
    if (key == "origin_m") ls >> x0 >> y0;
    else if (key == "resolution_m") ls >> resolution;
    else if (key == "size") ls >> cols >> rows;
    else throw std::runtime_error(path + ": unexpected header line '" + line + "'");
  }
  if (cols <= 0 || rows <= 0 || !(resolution > 0))
    throw std::runtime_error(path + ": missing origin_m / resolution_m / size");
  std::vector<double> values(static_cast<std::size_t>(cols) * rows);
  for (double& v : values) {
    if (!(in >> v)) throw std::runtime_error(path + ": fewer values than size says");
  }
  return [=](double x, double y) {
    const int c = static_cast<int>(std::floor((x - x0) / resolution));
    const int r = static_cast<int>(std::floor((y - y0) / resolution));
    if (c < 0 || r < 0 || c >= cols || r >= rows) return std::nan("");
    return values[static_cast<std::size_t>(r) * cols + c];
  };
}

SiteFigures EvaluateSite(const SiteEvalOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("SiteEvalOptions: " + why);
  const sim::Site site = sim::BuildSite(options.sim.seed, options.sim.terrain);
  SiteFigures figures;
  figures.map = AccumulateSessionA(options.sim, site, options.scan_stride);
  const sim::World world(site.terrain, sim::SessionPrimitives(site, sim::SessionId::kA),
                         options.sim.index_cell_m);
  const sim::SurfaceDistanceField field(world);
  if (options.measure_craft) {
    figures.craft = MeasureCrafting(options, figures.map, field, world.primitives());
  }
  if (!options.measure_ground_and_slope) return figures;

  // Ground filter on one return per voxel: original returns, so each keeps its hit label.
  const std::vector<std::size_t> kept = registration::UniformSampleIndices(
      ToFloat(figures.map.points_map), static_cast<float>(options.ground_voxel_m));
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i : kept) points.push_back(figures.map.points_map[i]);
  figures.ground_filter_points = points.size();
  const auto start = Clock::now();
  const terrain::GroundFilterResult split = terrain::ExtractGround(points, options.ground);
  figures.ground.seconds = SecondsSince(start);
  figures.ground.method = terrain::ToString(split.method);
  std::vector<Eigen::Vector3d> filter_ground, filter_objects, true_ground, true_objects;
  GroundFigures& g = figures.ground;
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const bool truth_ground = figures.map.is_ground[kept[k]] != 0;
    const bool said_ground = split.ok && split.labels[k] == terrain::GroundLabel::kGround;
    ++(truth_ground ? (said_ground ? g.ground_as_ground : g.ground_as_object)
                    : (said_ground ? g.object_as_ground : g.object_as_object));
    (said_ground ? filter_ground : filter_objects).push_back(points[k]);
    (truth_ground ? true_ground : true_objects).push_back(points[k]);
  }

  std::filesystem::create_directories(options.out_dir);
  const std::string slope_path = options.out_dir + "/site_slope.txt";
  sim::WriteSlopeGrid(slope_path, site, options.traversability.resolution_m);
  const evaluation::TruthField truth = ReadSimSlopeGrid(slope_path);
  const evaluation::TruthField footprint =
      FootprintSlope(site, options.traversability.surface.normal_radius_m);
  figures.slope_filter = MeasureSlope(options, truth, footprint, filter_ground, filter_objects,
                                      "ground_filter");
  figures.slope_truth =
      MeasureSlope(options, truth, footprint, true_ground, true_objects, "true_labels");
  figures.slope_truth_all_cells = MeasureSlope(options, truth, footprint, true_ground,
                                               true_objects, "true_labels_all_cells", true);
  return figures;
}

}  // namespace hylo::site_eval
