# When ctest starts each test.
#
# ctest -j starts the tests of highest COST first. After a run it takes each
# test's time from Testing/Temporary/CTestCostData.txt instead, but CI builds
# a clean clone, which has none: without these it would start the tests in
# the order they are declared and could leave a two-minute test for last, on
# one core while the other idles. Each entry: seconds on the sanitizer build of a clean
# clone, measured on 2026-12-07 on the 2-core machine (ctest -j2); only
# their order matters. Included by tests/CMakeLists.txt after
# the discovered GoogleTest tests; ctest passes over a name that is gone.
foreach(entry
    "186|packages"
    "173|help_examples"
    "83|planted_defects"
    "77|bad_inputs"
    "77|Gate.UnchangedBuildPassesTwiceOnBothApis"
    "70|gpu_scripts"
    "67|subtle_defects"
    "59|charts"
    "52|history_postgres"
    "41|ab_rounds"
    "37|GateInputs.KilledUpdatesLeaveTheOldSetOrTheNewSet"
    "35|Gate.HtmlReportOpensInHeadlessChromiumWithFailuresFirst"
    "35|Backends/KernelVsReference.Slats320x180/gl  # GetParam() = gl"
    "33|fleet_expectations"
    "32|Backends/KernelVsReference.Slats320x180/vk  # GetParam() = vk"
    "28|damaged_records"
    "27|Backends/KernelVsReference.Corner320x180/vk  # GetParam() = vk"
    "26|Backends/StageAgreement.ComputeAndFragmentAgree/vk  # GetParam() = vk"
    "26|Compare.AnEditedKernelOnOneSideIsMeasuredInItsPass"
    "25|Digests.MigrationKilledAnywhereLeavesAllOrNothing"
    "25|Backends/KernelVsReference.Corner320x180/gl  # GetParam() = gl"
    "24|killed_run"
    "24|store_http"
    "23|Backends/KernelVsReference.Slats160x90/vk  # GetParam() = vk"
    "22|Backends/KernelVsReference.Slats160x90/gl  # GetParam() = gl"
    "22|Backends/KernelVsReference.Corner160x90/vk  # GetParam() = vk"
    "22|Backends/StageAgreement.ComputeAndFragmentAgree/gl  # GetParam() = gl"
    "21|Backends/KernelVsReference.Corner160x90/gl  # GetParam() = gl"
    "19|TwoStep.EveryRepetitionIsJudgedAndMatchingOnesStoreNoImages"
    "17|TwoStep.JudgingARenderFolderGivesTheOneStepVerdictsAndMetrics"
    "17|GateInputs.ToleranceJudgesAgainstTheClassReferenceElseTheDefault"
    "17|History.BadInputsAreOneLineAndWriteNothing"
    "17|fleet_shard_protocols"
    "17|summary_and_status"
    "17|Compare.InterleavedRunsAlternateAndKeepTheSidesApart"
    "15|GateInputs.ApprovedDigestsPassAtOnceAndKnownBadOnesFail"
    "15|TwoStep.ShardsJudgedTogetherGiveTheWholeVerdict"
    "15|ImportCli.BadInputExitsTwoWithOneLineAndWritesNothing"
    "14|Backends/SdfAo.GroundTruthMatchesItsReference/vk  # GetParam() = vk"
    "14|coverage"
    "14|Backends/Analytic.OpenGeometryReadsOpenEverywhere/vk  # GetParam() = vk"
    "14|History.ARevertedSlowdownIsFoundAndDoesNotFailTheJob"
    "14|Backends/SdfAo.GroundTruthMatchesItsReference/gl  # GetParam() = gl"
    "14|Digests.AnFnvStoreMigratesInOneCommandAndStillPassesByDigest"
    "13|fleet_ctest_resources"
    "12|Backends/KernelVsReference.FusedTailMakesTheImagesOfUpsampleThenComposite/gl  # GetParam() = gl"
    "12|Backends/KernelVsReference.FusedTailMakesTheImagesOfUpsampleThenComposite/vk  # GetParam() = vk"
    "12|Backends/Analytic.OpenGeometryReadsOpenEverywhere/gl  # GetParam() = gl"
    "11|Backends/KernelVsReference.InterleavedLayersShadeAsThePlainReferenceDoes/vk  # GetParam() = vk"
    "11|fleet_flaky"
    "11|results_schema"
    "11|RunOutputs.SummaryReadsAsResultsJsonAndThePageShowsEveryConfiguration"
    "11|TwoStep.ImagesJudgedWhereTheyAreRenderedTravelAsVerdicts"
    "10|Cli.BadInputExitsTwoWithOneLineAndWritesNothing"
    "10|TwoStep.ApprovedDigestsTravelWithoutTheirImages"
    "10|Backends/KernelVsReference.InterleavedLayersShadeAsThePlainReferenceDoes/gl  # GetParam() = gl"
    "10|quality_page"
    "9|bundle"
    "9|TwoStep.BudgetsAreCheckedAgainstTheManifestTimes"
    "9|Assembled.EveryMatrixPassRunsTheRecordedGlslAndSpirv"
    "9|History.ChartPageIsSelfContained"
    "9|GateInputs.CpuBudgetOverrunIsReportedAndFailsOnlyWhenEnforced"
    "9|Backends/KernelVsReference.DefaultFastKernelsHoldTheStatedTolerance/gl  # GetParam() = gl"
    "9|Damages/BadRenderFolder.IsRefusedWithOneLineNamingTheFileAndWritesNothing/ManifestOfAnotherBuild  # GetParam() = 7"
    "9|readme_flags"
    "9|Backends/ImportRoundTrip.EveryScreenSpacePipelineMatchesTheGeneratedGBuffer/gl  # GetParam() = gl"
    "8|Backends/SdfAo.MoreSamplesDoNotRaiseTheErrorAgainstTheGroundTruth/vk  # GetParam() = vk"
    "8|Backends/KernelVsReference.BlurRadiiTiledAndNot/gl  # GetParam() = gl"
    "8|Backends/Analytic.CreaseFollowsTheTruthInEveryBand/vk  # GetParam() = vk"
    "8|Backends/ImportRoundTrip.EveryScreenSpacePipelineMatchesTheGeneratedGBuffer/vk  # GetParam() = vk"
    "8|Damages/BadRenderFolder.IsRefusedWithOneLineNamingTheFileAndWritesNothing/ManifestOfAnotherMatrix  # GetParam() = 5"
    "8|GateInputs.UpdateRewritesOnlyTheSelectedEntries"
)
  string(REPLACE "|" ";" pair "${entry}")
  list(GET pair 0 cost)
  list(GET pair 1 name)
  set_tests_properties("${name}" PROPERTIES COST ${cost})
endforeach()
