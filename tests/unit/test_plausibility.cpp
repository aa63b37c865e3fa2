// Plausibility of inputs (etfe/kernels/plausibility.h): each check is fine inside its range, warns
// outside it and refuses where no film can be; the message names the option (or file), the unit
// and, for a value off by a unit, the value meant.
#include <string>

#include "check.h"
#include "etfe/kernels/plausibility.h"
#include <vector>

using etfe::CheckCompensation;
using etfe::CheckMeshExtent;
using etfe::CheckThickness;
using etfe::CheckYield;
using etfe::CheckYoung;
using etfe::Plausibility;
using etfe::PlausibilityCheck;

namespace {

bool Says(const PlausibilityCheck &c, Plausibility level, const std::string &part) {
  return c.level == level && c.message.find(part) != std::string::npos;
}

std::vector<double> Square(double side) { return {0, 0, 0, side, 0, 0, side, side, 0, 0, side, 0}; }

etfe::PlausibilityCheck Extent(const std::vector<double> &coords, const std::string &file) {
  return CheckMeshExtent(coords.data(), (int)coords.size() / 3, file);
}

void TestMeshExtent() {
  CHECK(Extent(Square(2000.0), "a.msh").level == Plausibility::Fine, "a 2 m square");
  CHECK(Extent(Square(71.0), "a.msh").level == Plausibility::Fine, "diagonal 100.4 mm");
  CHECK(Extent(Square(7e5), "a.msh").level == Plausibility::Fine, "diagonal 990 m");
  const PlausibilityCheck m = Extent(Square(3.0), "roof.msh");
  CHECK(Says(m, Plausibility::Warning, "mesh roof.msh spans 4.24264 mm") && Says(m, Plausibility::Warning, "in m"),
        "a 3 m roof in m: %s", m.message.c_str());
  CHECK(Says(Extent(Square(3e6), "roof.msh"), Plausibility::Warning, "in um"), "a 3 km square");
  CHECK(CheckMeshExtent(nullptr, 0, "empty").level == Plausibility::Fine, "no nodes: nothing to say");
}

void TestThickness() {
  for (double h : {0.05, 0.1, 0.25, 0.5}) CHECK(CheckThickness(h).level == Plausibility::Fine, "%g mm", h);
  CHECK(Says(CheckThickness(0.00025), Plausibility::Error, "Did you mean 0.25 (the value in m)?"),
        "0.00025: %s", CheckThickness(0.00025).message.c_str());
  CHECK(Says(CheckThickness(250), Plausibility::Error, "Did you mean 0.25 (the value in um)?"), "250 um");
  CHECK(Says(CheckThickness(0.02), Plausibility::Warning, "-membrane_thickness 0.02: the thickness is in mm"),
        "0.02 mm: %s", CheckThickness(0.02).message.c_str());
  CHECK(Says(CheckThickness(1.0), Plausibility::Warning, "0.05-0.5 mm"), "1 mm");
  CHECK(Says(CheckThickness(12.0), Plausibility::Error, "no film"), "12 mm");
}

void TestMaterial() {
  for (double E : {100.0, 800.0, 5000.0}) CHECK(CheckYoung(E).level == Plausibility::Fine, "%g MPa", E);
  CHECK(Says(CheckYoung(8e8), Plausibility::Error, "Did you mean 800 (the value in Pa)?"), "8e8: %s",
        CheckYoung(8e8).message.c_str());
  CHECK(Says(CheckYoung(8e5), Plausibility::Warning, "Did you mean 800 (the value in kPa)?"), "8e5: %s",
        CheckYoung(8e5).message.c_str());
  CHECK(Says(CheckYoung(0.8), Plausibility::Warning, "Did you mean 800 (the value in GPa)?"), "0.8");
  const double thesis[2] = {13.28, 23.04}, low[2] = {3, 25}, pa[2] = {1.328e7, 2.304e7}, small[1] = {0.5};
  CHECK(CheckYield(thesis, 2, 800).level == Plausibility::Fine, "thesis Table 4.2");
  CHECK(CheckYield(low, 2, 800).level == Plausibility::Fine, "3,25 MPa");
  CHECK(Says(CheckYield(pa, 2, 800), Plausibility::Error, "Did you mean 13.28 (the value in Pa)?"), "in Pa: %s",
        CheckYield(pa, 2, 800).message.c_str());
  CHECK(Says(CheckYield(small, 1, 800), Plausibility::Warning, "-material_yield 0.5 (value 1)"), "0.5 MPa");
}

void TestCompensation() {
  for (double c : {0.0, 0.01, -0.02, 0.05})
    CHECK(CheckCompensation("-cutpattern_compensation_md", c).level == Plausibility::Fine, "%g", c);
  const PlausibilityCheck w = CheckCompensation("-cutpattern_compensation_td", 0.08);
  CHECK(Says(w, Plausibility::Warning, "-cutpattern_compensation_td 0.08: the compensation is a fraction (0.01 = 1 %)"),
        "8 %%: %s", w.message.c_str());
  const PlausibilityCheck e = CheckCompensation("-cutpattern_compensation_md", 1.0);
  CHECK(Says(e, Plausibility::Error, "this is 100 % and cuts the strips at 1/2 of the design") &&
            Says(e, Plausibility::Error, "Did you mean 0.01 (1 %)?"),
        "100 %%: %s", e.message.c_str());
  CHECK(CheckCompensation("-cutpattern_compensation_md", -0.6).level == Plausibility::Error, "-60 %%");
}

void TestLoads() {
  CHECK(etfe::CheckPrestress("-cutpattern_prestress", 5.0).level == Plausibility::Fine, "5 MPa");
  const PlausibilityCheck s = etfe::CheckPrestress("-cutpattern_prestress", 3000.0);
  CHECK(Says(s, Plausibility::Warning, "Did you mean 3 (the value in kPa)?"), "3000: %s", s.message.c_str());
  for (double p : {2e-4, -1e-3, 0.002, 0.05})
    CHECK(etfe::CheckPressure("scene x: the pressure", p).level == Plausibility::Fine, "%g MPa", p);
  const PlausibilityCheck w = etfe::CheckPressure("scene x: the pressure", 0.2);
  CHECK(Says(w, Plausibility::Warning, "scene x: the pressure reaches 0.2 MPa (200 kPa)") &&
            Says(w, Plausibility::Warning, "Did you mean 0.0002 MPa (a unit 1000 times smaller)?"),
        "0.2 MPa: %s", w.message.c_str());
  const PlausibilityCheck e = etfe::CheckPressure("scene x: the pressure", 2000.0);
  CHECK(Says(e, Plausibility::Error, "Did you mean 0.002 MPa (a unit 1e+06 times smaller)?"), "2000 MPa: %s",
        e.message.c_str());
}

void TestStructureValues() {
  const PlausibilityCheck g = CheckThickness(0.00025, "-film_roof_thickness");
  CHECK(Says(g, Plausibility::Error, "-film_roof_thickness 0.00025: the thickness is in mm") &&
            Says(g, Plausibility::Error, "Did you mean 0.25 (the value in m)?"),
        "per-group thickness in m: %s", g.message.c_str());
  for (double p : {50.0, 101.325, 110.0}) CHECK(etfe::CheckAtmosphere(p).level == Plausibility::Fine, "%g kPa", p);
  const PlausibilityCheck pa = etfe::CheckAtmosphere(101325);
  CHECK(Says(pa, Plausibility::Error, "Did you mean 101.325 (the value in Pa)?"), "101325: %s", pa.message.c_str());
  CHECK(Says(etfe::CheckAtmosphere(0.101325), Plausibility::Error, "Did you mean 101.325 (the value in MPa)?"),
        "0.101325: %s", etfe::CheckAtmosphere(0.101325).message.c_str());
  CHECK(Says(etfe::CheckAtmosphere(30), Plausibility::Warning, "-structure_atmosphere 30"), "30 kPa");
  for (double rho : {900.0, 1750.0, 2200.0}) CHECK(etfe::CheckDensity(rho).level == Plausibility::Fine, "%g", rho);
  const PlausibilityCheck d = etfe::CheckDensity(1.75);
  CHECK(Says(d, Plausibility::Error, "Did you mean 1750 (the value in g/cm^3)?"), "1.75: %s", d.message.c_str());
  CHECK(Says(etfe::CheckDensity(500), Plausibility::Warning, "-structure_density 500"), "500 kg/m^3");
  CHECK(etfe::CheckDensity(1e5).level == Plausibility::Error, "1e5 kg/m^3");
  for (double T : {-50.0, 20.0, 60.0, 150.0})
    CHECK(etfe::CheckTemperature("-material_temperature", T).level == Plausibility::Fine, "%g C", T);
  const PlausibilityCheck k = etfe::CheckTemperature("-material_temperature", 293.15);
  CHECK(Says(k, Plausibility::Error, "Did you mean 20 (the value in K)?"), "293.15: %s", k.message.c_str());
  CHECK(Says(etfe::CheckTemperature("-material_temperature", 1000), Plausibility::Error, "ETFE has melted"), "1000 C");
  CHECK(Says(etfe::CheckTemperature("-material_reference_temperature", 200), Plausibility::Warning,
             "-material_reference_temperature 200: the temperature is in deg C"),
        "200 C");
}

} // namespace

int main() {
  TestMeshExtent();
  TestThickness();
  TestMaterial();
  TestCompensation();
  TestLoads();
  TestStructureValues();
  TEST_MAIN_END();
}
