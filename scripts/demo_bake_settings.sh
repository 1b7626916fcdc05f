# The demo's bake settings, sourced by scripts/demo.sh and by the test that measures them
# (tests/cli/demo_quality_test.mjs), so the test checks what the demo bakes.
# Chosen by measurement (docs/baker.md, "The demo's bake"): at 4096 samples and cpca8@0.005 the
# room's exit radiance is within 0.5% RMS of an 8192-sample float bake under the city and forest
# maps, and its low-frequency error (patches) stays under 1% at the 99th percentile; at 1024
# samples and cpca8@0.015 (the settings before) it was 1.3% RMS with 2-9% patches.
demo_samples=${PRT_DEMO_SAMPLES:-4096}
demo_compress=${PRT_DEMO_COMPRESS:-cpca8@0.005}
# The glossy matrix passes' own setting (docs/baker.md, "The demo's bake"): a lobe-weighted 2%,
# about twice as tight as the glossy benchmark's 40 dB setting; the diffuse target (0.5%) would
# make the glossy asset four times larger for nothing one can see.
demo_compress_matrices=${PRT_DEMO_COMPRESS_MATRICES:-cpca16b8@0.02}
