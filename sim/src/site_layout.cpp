// The substation layout. Lanes (vehicle routes) run at y = 12, 47, 63 and x = 22, 93; the
// switchyard (gantries at x = 32..86 spanning y = 17..39, transformers at y = 55) lies
// between them; the annex plateau (x > 100, y < 40, 2.5 m high) is reached by a ramp at
// x = 107..114 from the north. Every object keeps >= 2 m from the lanes it borders.
#include "hylo/sim/site_layout.h"

#include <Eigen/Geometry>
#include <cmath>

#include "hylo/sim/random.h"
#include "site_structures.h"

namespace hylo::sim {
namespace {

namespace st = structures;
using V2 = Eigen::Vector2d;

TerrainShape MakeShape(Rng* rng) {
  TerrainShape shape;
  const auto j = [&](double s) { return rng->Uniform(-s, s); };
  shape.hills = {
      {V2(108.0 + j(1.0), 68.0 + j(1.0)), 6.0 + j(0.3), 8.0},  // NE hill, slopes to ~24 deg
      {V2(8.0 + j(1.0), 32.0 + j(1.0)), 3.5 + j(0.3), 6.0},    // W hill by the gate
      {V2(60.0 + j(3.0), 92.0), 4.0, 10.0},                    // beyond the north fence
      {V2(55.0 + j(2.0), 12.0), 0.4, 2.0},                     // bump on the south lane
      {V2(93.0, 30.0 + j(2.0)), 0.5, 2.5},                     // bump on the east lane
      {V2(45.0 + j(2.0), 47.0), -0.3, 2.0},                    // hollow on the mid lane
  };
  shape.ditches = {{V2(30.0, 68.0), V2(92.0, 68.0), 0.7, 1.0}};
  Plateau annex;
  annex.x_min_m = 100.0;
  annex.y_max_m = 40.0;
  annex.ramp_x_min_m = 107.0;
  annex.ramp_x_max_m = 114.0;
  shape.plateaus = {annex};
  shape.beds = {{V2(26.0, 10.0), V2(96.0, 62.0), 0.08, 0.1}};
  shape.trenches = {{V2(28.0, 43.5), V2(92.0, 43.5), 0.6, 0.5},
                    {V2(27.0, 14.0), V2(27.0, 43.5), 0.6, 0.5}};
  shape.undulation_phase = V2(rng->Uniform(0.0, 2.0 * M_PI), rng->Uniform(0.0, 2.0 * M_PI));
  return shape;
}

class Builder {
 public:
  Builder(Site* site, Rng* rng) : site_(site), rng_(rng) { site_->objects.reserve(256); }

  // Lowest ground under a disc of `radius` around xy, a little below so nothing floats.
  double Ground(const V2& xy, double radius) const {
    double z = site_->terrain->BaseHeight(xy.x(), xy.y());
    for (int k = 0; k < 8; ++k) {
      const V2 p = xy + radius * V2(std::cos(k * M_PI / 4), std::sin(k * M_PI / 4));
      z = std::min(z, site_->terrain->BaseHeight(p.x(), p.y()));
    }
    return z - 0.05;
  }
  V2 Jitter(const V2& xy) {
    return xy + V2(rng_->Uniform(-0.15, 0.15), rng_->Uniform(-0.15, 0.15));
  }
  st::Parts* Add(const std::string& kind, bool in_a = true, bool in_b = true) {
    site_->objects.push_back(SiteObject{kind, in_a, in_b, {}});
    return &site_->objects.back().parts;
  }

  void Switchyard() {
    const bool flip = rng_->Uniform() < 0.5;
    for (const double x : {32.0, 50.0, 68.0, 86.0}) {
      st::Parts* parts = Add("gantry");
      const V2 south(x, 17.0), north(x, 39.0);
      const double z_top = std::min(Ground(south, 0.6), Ground(north, 0.6)) + 11.0;
      st::AddLatticeTower(south, Ground(south, 0.6), z_top - Ground(south, 0.6), 0.8, parts);
      st::AddLatticeTower(north, Ground(north, 0.6), z_top - Ground(north, 0.6), 0.8, parts);
      st::AddLatticeGirder({x, 17.4, z_top - 0.4}, {x, 38.6, z_top - 0.4}, 0.8, parts);
      girder_z_ = z_top - 0.8;
    }
    for (const double y : {22.0, 28.0, 34.0}) {
      st::Parts* parts = Add("busbar");
      for (const double x : {32.0, 50.0, 68.0, 86.0}) {  // suspension insulator strings
        parts->push_back(
            MakeCylinder({x, y, girder_z_ - 1.6}, {x, y, girder_z_}, 0.08, st::kPorcelain));
      }
      parts->push_back(
          MakeCylinder({32.0, y, girder_z_ - 1.6}, {86.0, y, girder_z_ - 1.6}, 0.05, st::kSteel));
      for (const double x : {41.0, 59.0, 77.0}) {
        const V2 xy = Jitter(V2(x, y));
        st::AddInsulatorColumn(xy, Ground(xy, 0.2), Add("insulator_column"));
      }
    }
    const double xs_gantry[4] = {32.0, 50.0, 68.0, 86.0};
    int i = 0;
    for (const double x : {36.0, 52.0, 68.0, 84.0}) {
      const V2 xy = Jitter(V2(x, 55.0));
      const double yaw = flip ? M_PI : 0.0;
      const double base = Ground(xy, 3.0);
      st::AddTransformer(xy, base, yaw, Add("transformer"));
      const double bushing_y = xy.y() + (flip ? 0.6 : -0.6);
      st::AddSaggingCable({xs_gantry[i++], 38.6, girder_z_}, {x, bushing_y, base + 4.7}, 1.0, 0.02,
                          6, Add("cable"));
    }
  }

  void Perimeter() {
    const auto ground = [this](double x, double y) { return site_->terrain->BaseHeight(x, y); };
    const auto fence = [&](V2 a, V2 b, bool in_a, bool in_b) {
      st::AddFence(a, b, 3.0, ground, Add("fence", in_a, in_b));
    };
    fence(V2(1, 1), V2(119, 1), true, true);
    fence(V2(119, 1), V2(119, 43), true, true);
    fence(V2(119, 43), V2(119, 55), true, false);  // removed before session B
    fence(V2(119, 55), V2(119, 79), true, true);
    fence(V2(119, 79), V2(1, 79), true, true);
    fence(V2(1, 79), V2(1, 44), true, true);  // gate gap at y = 36..44
    fence(V2(1, 36), V2(1, 1), true, true);
  }

  void Buildings() {
    st::Parts* b = Add("control_building");
    const V2 c(10.5, 66.0);
    const double z = Ground(c, 8.0);
    b->push_back(MakeBox({c.x(), c.y(), z + 2.25}, {13.0, 12.0, 4.5}, 0.0, st::kConcrete));
    b->push_back(MakeBox({c.x(), c.y(), z + 4.6}, {13.6, 12.6, 0.2}, 0.0, st::kConcrete));
    b->push_back(MakeBox({17.2, 63.0, z + 1.0}, {0.6, 1.2, 1.2}, 0.0, st::kSteel));  // A/C unit
    for (const V2& p : {V2(24.5, 8.0), V2(58.0, 8.5), V2(96.0, 8.0), V2(19.5, 52.0), V2(60.0, 60.5),
                        V2(96.0, 66.0)}) {
      const double g = Ground(p, 0.2);
      Add("pole")->push_back(
          MakeCylinder({p.x(), p.y(), g}, {p.x(), p.y(), g + 8.0}, 0.1, st::kSteel));
    }
  }

  void Changes() {
    const V2 drum_a = Jitter(V2(30.0, 51.5)), drum_b = Jitter(V2(46.0, 51.5));
    st::AddCableDrum(drum_a, Ground(drum_a, 1.0), 0.0, Add("cable_drum", true, false));
    st::AddCableDrum(drum_b, Ground(drum_b, 1.0), 0.0, Add("cable_drum", false, true));
    const V2 van = Jitter(V2(65.0, 50.8));
    st::AddVehicle(van, Ground(van, 2.0), 0.0, Add("parked_vehicle", false, true));
    const V2 box = Jitter(V2(97.0, 55.0));
    Add("container", false, true)
        ->push_back(MakeBox({box.x(), box.y(), Ground(box, 3.0) + 1.295}, {6.06, 2.44, 2.59},
                            M_PI / 2, st::kContainer));
  }

  void Annex() {
    const V2 box(114.0, 22.0), shed(106.0, 4.5);
    Add("container")
        ->push_back(MakeBox({box.x(), box.y(), Ground(box, 3.0) + 1.295}, {6.06, 2.44, 2.59},
                            M_PI / 2, st::kContainer));
    Add("shed")->push_back(MakeBox({shed.x(), shed.y(), Ground(shed, 2.0) + 1.25}, {3.0, 3.0, 2.5},
                                   0.0, st::kConcrete));
    for (const V2& p : {V2(116.0, 8.0), V2(116.5, 30.0)}) {
      st::AddCableDrum(p, Ground(p, 1.0), M_PI / 2, Add("cable_drum"));
    }
    const V2 pole(107.3, 28.0);
    const double g = Ground(pole, 0.2);
    Add("pole")->push_back(
        MakeCylinder({pole.x(), pole.y(), g}, {pole.x(), pole.y(), g + 6.0}, 0.12, st::kSteel));
  }

 private:
  Site* site_;
  Rng* rng_;
  double girder_z_ = 10.0;
};

}  // namespace

std::string ToString(SessionId session) { return session == SessionId::kA ? "a" : "b"; }

Site BuildSite(uint64_t seed, const TerrainOptions& terrain_options) {
  Site site;
  Rng rng = Rng::Derive(seed, 0x517e);
  site.terrain = std::make_shared<const Terrain>(MakeShape(&rng), terrain_options, seed);
  Builder builder(&site, &rng);
  builder.Switchyard();
  builder.Perimeter();
  builder.Buildings();
  builder.Changes();
  builder.Annex();
  site.route_a = {V2(22, 26), V2(22, 12), V2(93, 12), V2(93, 47),
                  V2(22, 47), V2(22, 63), V2(93, 63)};
  site.route_b = {V2(40, 47),  V2(90, 47),  V2(110.5, 52), V2(110.5, 12),
                  V2(104, 12), V2(104, 36), V2(110.5, 38), V2(110.5, 54)};
  site.annex_min_m = V2(100.0, 0.0);
  site.annex_max_m = V2(120.0, 40.0);
  return site;
}

std::vector<Primitive> SessionPrimitives(const Site& site, SessionId session) {
  std::vector<Primitive> out;
  for (size_t i = 0; i < site.objects.size(); ++i) {
    const SiteObject& object = site.objects[i];
    if (session == SessionId::kA ? !object.in_a : !object.in_b) continue;
    for (Primitive p : object.parts) {
      p.object_id = static_cast<int32_t>(i);
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace hylo::sim
