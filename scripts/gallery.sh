#!/usr/bin/env bash
# Regenerates the figure gallery: runs every figure command (release build) at two-column width
# (7 in) into out/gallery/<command>/ as SVG and PNG (150 dpi), copies the PNGs into
# docs/img/gallery/ and rewrites docs/gallery.md. Takes a few minutes on 2 cores.
#
#   bash scripts/gallery.sh            # two columns (7 in)
#   SIZE=1 bash scripts/gallery.sh     # one column (3.5 in)
set -euo pipefail
cd "$(dirname "$0")/.."

SIZE="${SIZE:-2}"
DPI="${DPI:-150}"
OUT=out/gallery
IMG=docs/img/gallery
cargo build --release -p flexrig-cli
BIN=target/release/flexrig
mkdir -p "$OUT" "$IMG"

# name | command line (after `flexrig`) | what it shows
RUNS=(
  "experiment|experiment --repeats 5|The paper's Fig. 9 replayed: peak force of CJ and CL with the test-bed payload and the light load, and the paired CL/CJ ratio."
  "experiment_payload_1kg|experiment --repeats 3 --set robot.payload_kg=1.0 --set operator.block_mass_kg=4|The same with every scene's payload set to 1 kg and the block to 4 kg: the labels follow the values that ran."
  "fig6|fig6|The paper's Fig. 6: η(γ) for the eight design cases, n = 1 and 2."
  "eta|eta|η_FE of the Fig. 6 cases (finite elements) beside the lumped η(2/3), and the FE points on the Fig. 6 curves."
  "eta_map|eta-map --points 8|Maps of η_FE and the models' errors over m_e/m_r × k_δ/k_c, one figure per head mass."
  "eta_rotor|eta-rotor|η_FE from a freely pivoting link to the held joint over the rotor inertia."
  "payload|payload --points 13|The test bed's CJ and CL peaks and their ratio over the payload."
  "prb|prb|The PRB model's circle against the FE tip path, on equal axes."
  "spin_up|spin-up|The spin-up beam (Kane, Ryan & Banerjee 1987): the FE tip deflection in the hub frame against the elastica reference."
  "role_switch|role-switch|The role switch: the driven robot's peak over the test bed's against the drive's compliance, CJ and CL, for the test bed's link and the Fig. 6 cases."
  "safety_map|safety-map --region hands_and_fingers --material skinned_aluminium --m-r 0.051|The permissible speed near the back of the hand (ISO/TS 15066) of the CJ and the CL over payload × link stiffness, by the lumped energy method, and their ratio."
  "bench|bench --quick|Work–precision: run time against error of the lumped impact, the beam and the rig."
)

{
  echo "# Figure gallery"
  echo
  echo "Every figure \`flexrig\` draws, at the printed width \`--size $SIZE\` with text of at least"
  echo "8 pt, as PNG at $DPI dpi (the commands also write SVG and, with \`--format pdf\`, PDF)."
  echo "Regenerate with \`bash scripts/gallery.sh\` (\`SIZE=1\` for one column); the SVG, PNG and"
  echo "every other output are in \`out/gallery/<name>/\`."
  echo
} > docs/gallery.md

for run in "${RUNS[@]}"; do
  IFS='|' read -r name args what <<< "$run"
  dir="$OUT/$name"
  rm -rf "$dir"
  mkdir -p "$dir"
  echo "== flexrig $args" >&2
  # shellcheck disable=SC2086
  "$BIN" $args --out "$dir" --size "$SIZE" --format svg,png --dpi "$DPI" > "$dir/stdout.txt"
  {
    echo "## $name"
    echo
    echo "\`flexrig $args --size $SIZE --format svg,png\`: $what"
    echo
  } >> docs/gallery.md
  for png in "$dir"/*.png; do
    [ -e "$png" ] || continue
    base="$(basename "$png")"
    cp "$png" "$IMG/${name}__${base}"
    echo "![$name: $base](img/gallery/${name}__${base})" >> docs/gallery.md
    echo >> docs/gallery.md
  done
done
echo "Wrote docs/gallery.md and $(ls "$IMG" | wc -l) images in $IMG" >&2
