# Expected seconds of the long tests (one test per line, the longest first), so that ctest -jN
# starts them first even on a clean clone, where it has no timing data of its own yet (it then
# starts tests in the order they were defined, and a 100 s test started last makes a 100 s
# tail). Once build/Testing/Temporary/CTestCostData.txt exists, ctest uses its measured times
# instead. Figures of a full run on this 2-core machine (ctest -j2); only the order matters.
# The validation tests (defined at build time by gtest_discover_tests); the command-line and
# MPI tests get theirs in tests/CMakeLists.txt, where they are defined.
set_tests_properties("validation.PoiseuilleVirtualParticles.HoldTheFluidAtTheWall" PROPERTIES COST 115)
set_tests_properties("validation.Rules/Viscosity.KolmogorovFlowMatchesTheory/srd3d_a130_dt1" PROPERTIES COST 54)
set_tests_properties("validation.FhpVacf.LongTimeTailApproachesOneOverT" PROPERTIES COST 50)
set_tests_properties("validation.Rules/Viscosity.KolmogorovFlowMatchesTheory/srd2d_a140_dt0_5" PROPERTIES COST 43)
set_tests_properties("validation.Rules/Viscosity.KolmogorovFlowMatchesTheory/srd2d_a130_dt0_5" PROPERTIES COST 41)
set_tests_properties("validation.FhpColloid.HeldDiscVacfTailGoesAsInverseTime" PROPERTIES COST 38)
set_tests_properties("validation.Rules/Poiseuille.ViscosityFromTheProfile/at_a2d_dt0_02_n25_seed" PROPERTIES COST 31)
set_tests_properties("validation.Rules/Viscosity.KolmogorovFlowMatchesTheory/at_a3d_dt0_5_report" PROPERTIES COST 30)
set_tests_properties("validation.LgcaVacf1d.InfiniteSystemHasNoPlateau" PROPERTIES COST 28)
set_tests_properties("validation.Rules/Poiseuille.ViscosityFromTheProfile/at_a3d_dt0_01_n10_seed" PROPERTIES COST 25)
set_tests_properties("validation.Rules/Viscosity.KolmogorovFlowMatchesTheory/at_a2d_dt0_5_report" PROPERTIES COST 24)
set_tests_properties("validation.PoiseuilleSeed000.Figure3_6" PROPERTIES COST 24)
set_tests_properties("validation.Rules/Poiseuille.ViscosityFromTheProfile/at3d_dt0_5" PROPERTIES COST 24)
set_tests_properties("validation.Rules/Viscosity.KolmogorovFlowMatchesTheory/at3d_dt0_5" PROPERTIES COST 23)
set_tests_properties("validation.Rules/Viscosity.KolmogorovFlowMatchesTheory/at2d_dt0_5" PROPERTIES COST 22)
set_tests_properties("validation.Rules/Poiseuille.ViscosityFromTheProfile/at2d_dt0_5" PROPERTIES COST 21)
set_tests_properties("validation.Rules/Poiseuille.ViscosityFromTheProfile/srd2d_a140_dt1" PROPERTIES COST 19)
set_tests_properties("validation.Rules/Poiseuille.ViscosityFromTheProfile/srd2d_a130_dt1" PROPERTIES COST 19)
set_tests_properties("validation.Sizes/LgcaVacf1dPlateau.ZeroMomentumGivesMinusOneMinusDOverN/L2000" PROPERTIES COST 19)
set_tests_properties("validation.Sizes/LgcaVacf1dPlateau.IndependentOccupationsCancelThePlateau/L2000" PROPERTIES COST 19)
set_tests_properties("validation.Rules/Viscosity.KolmogorovFlowMatchesTheory/srd3d_a90_dt1" PROPERTIES COST 17)
set_tests_properties("validation.FhpViscosity.HalfFillingRegressionAgainstOwnEarlierRun" PROPERTIES COST 14)
set_tests_properties("validation.FhpViscosity.FhpIIIHalfFillingIsBoltzmann" PROPERTIES COST 13)
set_tests_properties("validation.Rules/Poiseuille.ViscosityFromTheProfile/at_a2d_dt0_01_n50_seed_report" PROPERTIES COST 12)
set_tests_properties("validation.Rules/Poiseuille.ViscosityFromTheProfile/srd3d_a90_dt1" PROPERTIES COST 11)
set_tests_properties("validation.Rules/Poiseuille.ViscosityFromTheProfile/srd3d_a130_dt1" PROPERTIES COST 9)
set_tests_properties("validation.Srd/SelfDiffusion.MatchesKineticTheory/srd3d_a90_dt1" PROPERTIES COST 9)
set_tests_properties("validation.Rules/Viscosity.KolmogorovFlowMatchesTheory/srd2d_a90_dt1_expected_deviation" PROPERTIES COST 8)
set_tests_properties("validation.Srd/SelfDiffusion.MatchesKineticTheory/srd3d_a130_dt0_5" PROPERTIES COST 8)
set_tests_properties("validation.ColloidHardCase.TouchingStartUnderStrongGravity" PROPERTIES COST 7)
set_tests_properties("validation.Rules/Poiseuille.ViscosityFromTheProfile/srd2d_fig3_7_report" PROPERTIES COST 6)
set_tests_properties("validation.RunScenes/HardCaseLongRun.InvariantsHoldEvery100StepsFor1e5Steps/seed001_ata_3d" PROPERTIES COST 5)
