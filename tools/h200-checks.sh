# The GPU-shaped-work measurements (issue 44), sourced by ../shared/device/on-gpu on the H200:
#   ../shared/device/prepare tools/h200-checks.sh   (here), then on the GPU machine
#   BUDGET=330 .gpu/on-gpu .gpu/checks.sh
# `step NAME LIMIT_S COMMAND...`; $SSGI is the binary, $R the results folder. S512 and S1080
# shrink the sizes for a trial on lavapipe (ALLOW_CPU=1), most important step first.
S512=${S512:-512x512}
S1080=${S1080:-1920x1080}
# `step` runs its command under `timeout`, which takes programs, not shell functions.
for lanes in 16 1 4 64; do
  step orbit512-lanes$lanes 30 $SSGI bench --scene cornell-box --size $S512 --path orbit \
    --warmup converged --frames 240 --compare-reuse --vpl-lanes $lanes \
    --json $R/orbit512-lanes$lanes.json
done
step sponza1080 40 $SSGI bench --scene scenes/sponza.toml --size $S1080 --warmup converged \
  --frames 240 --compare-reuse --json $R/sponza1080.json
step sponza1080-lanes64 40 $SSGI bench --scene scenes/sponza.toml --size $S1080 \
  --warmup converged --frames 240 --compare-reuse --vpl-lanes 64 --json $R/sponza1080-lanes64.json
step boxpath1080 40 $SSGI bench --scene box:bunny --path paths/box.json --size $S1080 \
  --frames 240 --compare-reuse --json $R/boxpath1080.json
step val-ccipca 40 $SSGI --validation bench --scene cornell-box --path orbit \
  --indirect-filter ccipca --aa sraa-shadow --frames 20 --warmup 5
step val-all 40 $SSGI --validation bench --scene scenes/sponza.toml --size $S512 --frames 30 --warmup 5
step val-ssdo 40 $SSGI --validation bench --scene box:bunny --effects direct,ssdo \
  --ssdo-samples adaptive --path paths/box.json --frames 40 --warmup 5
step t41 120 $SSGI table thesis-4.1 --size $S512 --out $R/thesis-4.1
step walk 150 $SSGI table thesis-walkthroughs --size $S512 --out $R/walkthroughs
