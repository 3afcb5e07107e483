# The GPU-shaped-work measurements (issue 44), sourced by ../shared/device/on-gpu on the H200:
#   ../shared/device/prepare tools/h200-checks.sh   (here), then on the GPU machine
#   BUDGET=600 .gpu/on-gpu .gpu/checks.sh
# `step NAME LIMIT_S COMMAND...`; $SSGI is the binary, $R the results folder. S512 and S1080
# shrink the sizes for a trial on lavapipe (ALLOW_CPU=1), most important step first.
S512=${S512:-512x512}
S1080=${S1080:-1920x1080}
# `step` runs its command under `timeout`, which takes programs, not shell functions.
# Most important first: the visibility-buffer G-buffer against the raster one (the G-buffer was
# 58-66% of the reuse frame on the H200 and its time followed the bytes written per pixel), on
# the orbit and Sponza at 1080p, each mode in its own process beside its reuse comparison; then
# thesis-4.1 again at HEAD (the last run's first row ran at a low clock) and the walkthroughs;
# then ground-truth AO; then the refresh tiles' cost with whole 16x16 tiles (--refresh-budget 1)
# and validation.
step orbit512 30 $SSGI bench --scene cornell-box --size $S512 --path orbit \
  --warmup converged --frames 240 --compare-reuse --json $R/orbit512.json
step orbit512-vis 30 $SSGI bench --scene cornell-box --size $S512 --path orbit \
  --warmup converged --frames 240 --compare-reuse --gbuffer visibility --json $R/orbit512-vis.json
step sponza1080 40 $SSGI bench --scene scenes/sponza.toml --size $S1080 --warmup converged \
  --frames 240 --compare-reuse --json $R/sponza1080.json
step sponza1080-vis 40 $SSGI bench --scene scenes/sponza.toml --size $S1080 --warmup converged \
  --frames 240 --compare-reuse --gbuffer visibility --json $R/sponza1080-vis.json
step val-vis 40 $SSGI --validation bench --scene box:bunny --path paths/box.json \
  --gbuffer visibility --frames 40 --warmup 5
# Ground-truth AO beside the thesis's estimator along the orbit (issue 47: its GPU cost with
# and without the cache, and its error against the ray-traced AO), under validation first.
step val-gtao 40 $SSGI --validation bench --scene box:bunny --path paths/box.json --ao gtao \
  --frames 40 --warmup 5
step gtao512 90 $SSGI sweep --scene cornell-box --size $S512 --path orbit --effects ao \
  --frames 120 --warmup converged --vary ao.estimator=thesis,gtao --vary temporal.reuse=on,off \
  --out $R/gtao512
# SVGF beside CCIPCA and the joint bilateral filters (issue 47: its cost on a GPU, where the
# filters' full-screen passes are priced by bandwidth, not by lavapipe's CPU time), under
# validation first; then the AO estimators' table (its ground truth is traced on the CPU).
step val-svgf 40 $SSGI --validation bench --scene cornell-box --path orbit \
  --indirect-filter svgf --vpls 4 --frames 20 --warmup 5
step flicker 90 $SSGI table chang-flicker --out $R/chang-flicker
step t-ao 150 $SSGI table ao --out $R/ao
step t41 120 $SSGI table thesis-4.1 --size $S512 --out $R/thesis-4.1
step walk 150 $SSGI table thesis-walkthroughs --size $S512 --out $R/walkthroughs
step orbit512-budget1 30 $SSGI bench --scene cornell-box --size $S512 --path orbit \
  --warmup converged --frames 240 --refresh-budget 1 --json $R/orbit512-budget1.json
step val-ccipca 40 $SSGI --validation bench --scene cornell-box --path orbit \
  --indirect-filter ccipca --ccipca-orthogonalize always --aa sraa-shadow --frames 20 --warmup 5
step val-all 40 $SSGI --validation bench --scene scenes/sponza.toml --size $S512 --frames 30 --warmup 5
step val-ssdo 40 $SSGI --validation bench --scene box:bunny --effects direct,ssdo \
  --ssdo-samples adaptive --path paths/box.json --frames 40 --warmup 5
