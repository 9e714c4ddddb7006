# When ctest starts each test.
#
# ctest -j starts the tests of highest COST first. After a run it takes each
# test's time from Testing/Temporary/CTestCostData.txt instead, but CI builds
# a clean clone, which has none: without these it would start the tests in
# the order they are declared and could leave a two-minute test for last, on
# one core while the other idles. Each entry: seconds on the sanitizer build, measured on
# 2026-12-02 on the 2-core machine under load (about 2.5 times the CI
# figures); only their order matters. Included by tests/CMakeLists.txt after
# the discovered GoogleTest tests; ctest passes over a name that is gone.
foreach(entry
    "506|Gate.UnchangedBuildPassesTwiceOnBothApis"
    "350|gpu_scripts"
    "160|planted_defects"
    "130|charts"
    "100|history_postgres"
    "85|packages"
    "75|bundle"
    "70|Compare.AnEditedKernelOnOneSideIsMeasuredInItsPass"
    "50|Compare.InterleavedRunsAlternateAndKeepTheSidesApart"
    "45|summary_and_status"
    "43|GateInputs.ApprovedDigestsPassAtOnceAndKnownBadOnesFail"
    "296|GateInputs.KilledUpdatesLeaveTheOldSetOrTheNewSet"
    "169|bad_inputs"
    "161|Backends/KernelVsReference.Slats320x180/vk  # GetParam() = vk"
    "149|Gate.HtmlReportOpensInHeadlessChromiumWithFailuresFirst"
    "149|Backends/StageAgreement.ComputeAndFragmentAgree/vk  # GetParam() = vk"
    "147|Backends/KernelVsReference.Slats320x180/gl  # GetParam() = gl"
    "129|Backends/KernelVsReference.Corner320x180/vk  # GetParam() = vk"
    "127|fleet_flaky"
    "126|Backends/KernelVsReference.Slats160x90/vk  # GetParam() = vk"
    "116|Backends/StageAgreement.ComputeAndFragmentAgree/gl  # GetParam() = gl"
    "114|Backends/KernelVsReference.Corner320x180/gl  # GetParam() = gl"
    "108|Backends/KernelVsReference.Slats160x90/gl  # GetParam() = gl"
    "97|fleet_bisect"
    "95|fleet_expectations"
    "90|Backends/KernelVsReference.Corner160x90/vk  # GetParam() = vk"
    "68|Backends/KernelVsReference.Corner160x90/gl  # GetParam() = gl"
    "67|GateInputs.UpdateRewritesOnlyTheSelectedEntries"
    "58|TwoStep.JudgingARenderFolderGivesTheOneStepVerdictsAndMetrics"
    "53|TwoStep.EveryRepetitionIsJudgedAndMatchingOnesStoreNoImages"
    "50|TwoStep.ShardsJudgedTogetherGiveTheWholeVerdict"
    "48|fleet_ctest_resources"
    "45|Cli.BadInputExitsTwoWithOneLineAndWritesNothing"
    "43|Backends/KernelVsReference.OtherScenes160x90/vk  # GetParam() = vk"
    "42|Cli.HelpOnEveryCommandPrintsToStdoutAndExitsZero"
    "41|Backends/KernelVsReference.OtherScenes160x90/gl  # GetParam() = gl"
    "40|GateInputs.InterruptedUpdateLeavesTheOldFileWhole"
    "39|Cli.UnknownFlagNamesItsNearestNeighbour"
    "37|ImportCli.BadInputExitsTwoWithOneLineAndWritesNothing"
    "35|fleet_shard_protocols"
    "35|Compare.BadInputExitsTwoWithOneLineNamingIt"
    "31|Backends/Analytic.OpenGeometryReadsOpenEverywhere/vk  # GetParam() = vk"
    "30|GateInputs.CpuBudgetOverrunIsReportedAndFailsOnlyWhenEnforced"
    "29|charts"
    "28|GateInputs.UpdateFromAnIncompleteOutputChangesNothing"
    "27|Cli.ListPrintsExactlyWhatTheRunRuns"
    "26|Bench.RepetitionsShareOneClockAndEveryPassHasAnEntry"
    "26|Backends/RasterGBuffer.MatchesTheRayMarchedGBuffer/vk  # GetParam() = vk"
    "25|TwoStep.BudgetsAreCheckedAgainstTheManifestTimes"
    "24|Backends/RasterGBuffer.MatchesTheRayMarchedGBuffer/gl  # GetParam() = gl"
    "22|GateInputs.MissingBaselineIsBadInputNamingTheFile"
    "21|TwoStep.OverlappingShardsAreRefused"
    "21|Gate.DitherRemovedFailsOnDifferingPixelsWithAMargin"
    "20|Cli.QualityBadInputExitsTwoWithOneLine"
    "20|Backends/Analytic.CreaseFollowsTheTruthInEveryBand/vk  # GetParam() = vk"
    "18|results_schema"
    "18|Backends/SdfAo.MoreSamplesDoNotRaiseTheErrorAgainstTheGroundTruth/vk  # GetParam() = vk"
    "18|Backends/ScreenSpaceProperties.HalfResolutionStaysCloseToFullAtSilhouettes/vk  # GetParam() = vk"
    "18|Backends/Analytic.CreaseFollowsTheTruthInEveryBand/gl  # GetParam() = gl"
    "17|Cli.ProgressLinesAppearInAPipe"
    "17|Backends/SdfAo.MoreSamplesDoNotRaiseTheErrorAgainstTheGroundTruth/gl  # GetParam() = gl"
    "17|Backends/SdfAo.GroundTruthMatchesItsReference/vk  # GetParam() = vk"
    "17|Backends/SdfAo.GroundTruthMatchesItsReference/gl  # GetParam() = gl"
    "17|Backends/ScreenSpaceProperties.HalfResolutionStaysCloseToFullAtSilhouettes/gl  # GetParam() = gl"
    "17|Backends/Analytic.OpenGeometryReadsOpenEverywhere/gl  # GetParam() = gl"
    "16|junit_schema"
    "16|TwoStep.QualityOnTheRenderBinaryWritesTheSameQualityJson"
    "16|Cli.RunWritesImagesAndResults"
    "16|Bench.SmokeRunOnBothApisWithManualTimeFromTimestamps"
    "16|Backends/Timing.FourTimesThePixelsTakesAtLeastTwiceTheTime/vk  # GetParam() = vk"
    "16|Backends/Timing.BatchedAndDrainedGiveTheSameImagesAndSampleCounts/gl  # GetParam() = gl"
    "15|Backends/ImportRoundTrip.EveryScreenSpacePipelineMatchesTheGeneratedGBuffer/gl  # GetParam() = gl"
    "14|TwoStep.FoldersOfTwoBuildsAreRefused"
    "14|Gate.HtmlReportInlinesGateJsonThatNoMessageBreaksOutOf"
    "14|Backends/ImportRoundTrip.EveryScreenSpacePipelineMatchesTheGeneratedGBuffer/vk  # GetParam() = vk"
    "13|Compare.KnownShiftIsSlowerAndTheRestIsSame"
    "13|Backends/Timing.APlantedSlowdownLeavesEveryImageUnchanged/vk  # GetParam() = vk"
    "13|Backends/Properties.BilateralBlurOfAConstantIsThatConstant/vk  # GetParam() = vk"
    "12|RunSweep.EveryKernelParameterSweeps"
    "11|Backends/SdfAo.OpenSceneIsUnoccludedForEveryKernel/vk  # GetParam() = vk"
    "11|Backends/Properties.BilateralBlurDoesNotCarryAoAcrossADepthStep/vk  # GetParam() = vk"
    "11|Backends/KernelVsReference.DepthPyramidLevels/vk  # GetParam() = vk"
    "10|RenderBinary.LinksNoOpenImageIO"
    "10|Backends/Timing.APlantedSlowdownLeavesEveryImageUnchanged/gl  # GetParam() = gl"
    "10|Backends/SdfAo.ContactDarkensTheTableBesideTheSphere/vk  # GetParam() = vk"
    "10|Backends/Properties.BilateralBlurOfAConstantIsThatConstant/gl  # GetParam() = gl"
)
  string(REPLACE "|" ";" pair "${entry}")
  list(GET pair 0 cost)
  list(GET pair 1 name)
  set_tests_properties("${name}" PROPERTIES COST ${cost})
endforeach()

# test_render is SERIAL (tests/CMakeLists.txt), but these of its tests judge
# no time: a damaged or mismatched render folder, or a bad flag, is refused
# with exit 2 before anything is judged; the render binary's libraries; an
# image file's bytes. Each process works in its own folder (named by its
# pid), so they run beside other tests, as test_render's budgets of 1e6 ms
# would let its other tests too (they were a large part of the serial
# tests' time).
foreach(name
    "TwoStep.OverlappingShardsAreRefused"
    "TwoStep.FoldersOfTwoBuildsAreRefused"
    "TwoStep.BadRenderFlagsExitTwoWithOneLineAndWriteNothing"
    "RenderBinary.LinksNoOpenImageIO"
    "ImageFile.RoundTripsEveryBitInTheNarrowestForm"
    # test_gate is SERIAL for the budgets an unchanged build must pass; the
    # report test asserts that the failing configurations come first and
    # that there are some, which a budget overrun under load cannot break;
    # the other two run no gate. The unchanged build's two runs, the
    # longest test (a large part of a CI run, with the other core idle
    # throughout), judge images and determinism: on a software
    # renderer a budget overrun is reported, not failed
    # (GateOptions::enforceCpuBudgets), so load cannot fail them either.
    "Gate.UnchangedBuildPassesTwiceOnBothApis"
    "Gate.HtmlReportOpensInHeadlessChromiumWithFailuresFirst"
    "Gate.HtmlReportInlinesGateJsonThatNoMessageBreaksOutOf"
    "Gate.ShardsPartitionTheMatrix")
  set_tests_properties("${name}" PROPERTIES RUN_SERIAL FALSE)
endforeach()
# Named as gtest_discover_tests names them, with the parameter's index.
set(index 0)
foreach(damage MissingImage WrongSize TruncatedFile CorruptFile DigestMismatch ManifestOfAnotherMatrix
        ManifestOfAnEditedMatrix ManifestOfAnotherBuild ManifestOfAnotherSchema NoManifest FileOutsideTheFolder)
  set_tests_properties("Damages/BadRenderFolder.IsRefusedWithOneLineNamingTheFileAndWritesNothing/${damage}  # GetParam() = ${index}"
                       PROPERTIES RUN_SERIAL FALSE)
  math(EXPR index "${index} + 1")
endforeach()
