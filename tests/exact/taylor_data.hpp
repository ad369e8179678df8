// Measured data of the classic OFHC copper Taylor anvil test (a cylinder fired end-on at a
// rigid anvil), for tests/test_taylor.cpp and configs/taylor_anvil.yaml. Units cm, us.
//
// Source: G. R. Johnson and W. H. Cook, "A constitutive model and data for metals subjected to
// large strains, high strain rates and high temperatures", Proc. 7th Int. Symp. on Ballistics,
// The Hague, 1983, pp. 541-547 (the cylinder-impact test the Johnson-Cook OFHC copper constants
// were checked against). The paper itself could not be opened here. The numbers were read in
// the table of F. J. Zerilli and R. W. Armstrong, "Dislocation-mechanics-based constitutive
// relations for material dynamics calculations", J. Appl. Phys. 61 (1987) 1816-1825, which
// lists the Johnson & Cook (1983) / Johnson & Holmquist (1988) OFHC copper cylinders at 130,
// 146 and 190 m/s as L/L0 and D/D0 ratios, as transcribed in B. Banerjee's public data set
// (github.com/bbanerjee/HighRateExptData, TaylorData/MATLAB/plotOFHCCu.m, "zerilliData", whose
// comment says the data are Johnson & Cook's 1983 tests; used in B. Banerjee, "An evaluation of
// plastic flow stress models for the simulation of high-temperature and high-strain-rate
// deformation of metals", arXiv cond-mat/0512466). The same geometry and speed (2.54 cm long,
// 0.762 cm diameter, 190 m/s, OFHC copper) are the Sandia Sierra/SM Taylor anvil ensemble's
// (sandialabs/slycat, docs/manual/TAISDataSet.rst), which compares with the same experiment.
//
// Measurement uncertainty is not stated in the transcription; the ratios are given to 3
// digits (0.638, 1.78), i.e. +-0.1 % and +-0.3 % of rounding. For scale only: repeated OFHC
// copper shots of House et al. (Int. J. Impact Engng 16 (1995) 189, same transcription) at
// 176/176 m/s and 188/189 m/s recovered lengths 58.7/58.3 mm and 41.9/41.7 mm (0.5-0.7 %).
//
// Not pinned to a source and not used: Wilkins & Guinan (J. Appl. Phys. 44 (1973) 1200)
// copper, L0 2.347 cm, D0 0.762 cm, 210 m/s, L/L0 0.643 appears in the same transcription, but
// its footprint diameter there (1.658 cm) was digitised from a profile figure, not a table.
#pragma once

namespace mp::exact::taylor {

// Johnson & Cook (1983) OFHC copper cylinder, 190 m/s, room temperature (295 K in the table).
inline constexpr double kLength0 = 2.54;        // initial length, cm (25.4 mm)
inline constexpr double kDiameter0 = 0.762;     // initial diameter, cm (7.62 mm)
inline constexpr double kSpeed = 0.019;         // impact speed, cm/us (190 m/s)
inline constexpr double kDensity = 8.92;        // g/cm^3 as tabulated (the library's is 8.93)
inline constexpr double kLengthRatio = 0.638;   // final length / initial length, measured
inline constexpr double kDiameterRatio = 1.78;  // footprint (impact-face) diameter / D0, measured
inline constexpr double kLengthFinal = kLengthRatio * kLength0;            // 1.6205 cm
inline constexpr double kFootprintDiameter = kDiameterRatio * kDiameter0;  // 1.3564 cm

}  // namespace mp::exact::taylor
