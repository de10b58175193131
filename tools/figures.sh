#!/usr/bin/env bash
# Regenerates every figure the README quotes, from the bundled policies and models, into one
# JSON file (figures.json), and with --write puts them where the repository keeps them: each
# policy's eval.json (with the checkpoint's sha256) and the README block between
# <!-- figures:begin --> and <!-- figures:end -->.
#
#   tools/figures.sh [--out DIR] [--write] [--quick]
#
# --quick runs 10 trials / 2 story seeds / 3 stories per difficulty / no retrieval instead of
# 100 / 10 / 30 (a smoke test; its figures are not the README's). Every command's seed is fixed, so a rerun on the same machine
# reproduces the figures; another CPU may move them slightly (float kernels differ).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BIN="${SIMS_BIN:-$ROOT/build/bin}"
OUT="$ROOT/runs/figures"
WRITE=0
TRIALS=100
SEEDS=10
STORIES=30
RETRIEVAL=1
while [ $# -gt 0 ]; do
  case "$1" in
    --out) OUT="$2"; shift 2 ;;
    --write) WRITE=1; shift ;;
    --quick) TRIALS=10; SEEDS=2; STORIES=3; RETRIEVAL=0; shift ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    *) echo "figures.sh: unknown argument '$1' (expected --out DIR, --write, --quick)" >&2; exit 2 ;;
  esac
done
for tool in eval_policy run_story eval_story text_to_style; do
  [ -x "$BIN/$tool" ] || { echo "figures.sh: $BIN/$tool missing: run bash cmake/build.sh first" >&2; exit 1; }
done
cd "$ROOT"
mkdir -p "$OUT"
POLICIES=assets/policies/policies.json
EVAL_SEED=777
STORY=assets/stories/tired_evening.json
start=$(date +%s)
step() { echo "[figures $(( $(date +%s) - start )) s] $*" >&2; }

# 1. Every bundled policy: eval_policy, N trials, seed 777 (held-out objects for object skills).
skills=$(python3 -c "import json,sys; print(' '.join(json.load(open(sys.argv[1]))['policies']))" "$POLICIES")
for skill in $skills; do
  ckpt="assets/policies/$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['policies'][sys.argv[2]])" "$POLICIES" "$skill")"
  # A policy keeps the start protocol of its bundled evaluation (get-up: half its trials from
  # seated/lying clip states, --reference-starts 0.5), so --write replaces it like for like.
  bundled="$(dirname "$ckpt")/eval.json"
  starts=0
  [ -f "$bundled" ] && starts=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1])).get('reference_starts', 0))" "$bundled")
  # And the action smoothing the policy set gives it, where it does (what the stories run;
  # otherwise the policy's own).
  smoothing=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1])).get('action_smoothing', {}).get(sys.argv[2], -1))" "$POLICIES" "$skill")
  step "eval_policy $skill ($TRIALS trials, seed $EVAL_SEED, reference starts $starts, action smoothing $smoothing)"
  "$BIN/eval_policy" --checkpoint "$ckpt" --trials "$TRIALS" --seed "$EVAL_SEED" \
    --reference-starts "$starts" --action-smoothing "$smoothing" --out "$OUT/eval_$skill.json" \
    --log-level warn > /dev/null
done

# 2. The main command's story over seeds 0..SEEDS-1.
for ((s = 0; s < SEEDS; ++s)); do
  step "run_story $STORY --seed $s"
  "$BIN/run_story" "$STORY" --seed "$s" --out "$OUT/story_seed$s" --log-level warn > /dev/null
done

# 2b. SIMS Table 2 protocol: STORIES stories per difficulty from seed 0, batched (eval_story also
# writes its HTML table beside the JSON).
step "eval_story --stories $STORIES --seed 0"
"$BIN/eval_story" --stories "$STORIES" --seed 0 --out "$OUT/eval_story.json" --log-level warn \
  > /dev/null

# 3. Caption retrieval of the bundled motion-text model, dev and test paraphrase sets apart.
if [ "$RETRIEVAL" = 1 ] && [ ! -f data/language/text_motion/model.json ] &&
   [ ! -f assets/language/text_motion/model.json ]; then
  step "no motion-text model (data/ or assets/language/text_motion): retrieval skipped"
  RETRIEVAL=0
fi
if [ "$RETRIEVAL" = 1 ]; then
  for set in dev test; do
    file="configs/language/${set}_paraphrases.json"
    [ -f "$file" ] || continue
    step "text_to_style --eval $file"
    "$BIN/text_to_style" --eval "$file" --json > "$OUT/retrieval_$set.json"
  done
fi

# 4. One JSON with everything, commands and seeds included.
python3 - "$OUT" "$skills" "$TRIALS" "$SEEDS" "$EVAL_SEED" "$STORY" "$STORIES" <<'PY'
import glob, json, os, sys
out, skills, trials, seeds, eval_seed, story, stories = sys.argv[1:8]
fig = {"policies": {}, "story": {}, "retrieval": {}, "stories": {}}
e = json.load(open(os.path.join(out, "eval_story.json")))
fig["stories"] = {"command": f"eval_story --stories {stories} --seed 0",
                  "per_difficulty": e["per_difficulty"], "per_skill": e.get("per_skill", {}),
                  "reference_foot_sliding_m_per_s": e.get("reference_foot_sliding_m_per_s")}
for skill in skills.split():
    e = json.load(open(os.path.join(out, f"eval_{skill}.json")))
    fig["policies"][skill] = {k: e[k] for k in (
        "skill", "scene", "trials", "seed", "success_rate", "fall_rate", "contact_error",
        "time_to_success_s", "checkpoint", "checkpoint_sha256", "reference_starts",
        "action_smoothing") if k in e}
    starts = e.get("reference_starts", 0)
    smoothing = e.get("action_smoothing", 0)
    fig["policies"][skill]["command"] = (
        f"eval_policy --checkpoint {e['checkpoint']} --trials {trials} --seed {eval_seed}"
        + (f" --reference-starts {starts}" if starts else "")
        + (f" --action-smoothing {smoothing:g}" if smoothing else ""))
done, total, per_seed = 0, 0, []
for s in range(int(seeds)):
    r = json.load(open(os.path.join(out, f"story_seed{s}", "result.json")))
    k = r["keyframes"]
    ok = sum(1 for x in k if x.get("success"))
    per_seed.append({"seed": s, "keyframes": len(k), "succeeded": ok, "falls": r.get("falls", 0)})
    done += ok
    total += len(k)
fig["story"] = {"script": story, "seeds": int(seeds), "keyframes": total, "succeeded": done,
                "per_seed": per_seed, "command": f"run_story {story} --seed S (S = 0..{int(seeds)-1})"}
for path in sorted(glob.glob(os.path.join(out, "retrieval_*.json"))):
    name = os.path.basename(path)[len("retrieval_"):-len(".json")]
    r = json.load(open(path))
    fig["retrieval"][name] = {"correct": r["correct"], "total": r["total"],
                              "accuracy": r["accuracy"],
                              "command": f"text_to_style --eval configs/language/{name}_paraphrases.json"}
json.dump(fig, open(os.path.join(out, "figures.json"), "w"), indent=1, sort_keys=True)
PY
step "wrote $OUT/figures.json"

# 5. --write: bundled eval files and the README block.
if [ "$WRITE" = 1 ]; then
  for skill in $skills; do
    dir="$(dirname "$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['policies'][sys.argv[2]])" "$POLICIES" "$skill")")"
    cp "$OUT/eval_$skill.json" "assets/policies/$dir/eval.json"
  done
  python3 - "$OUT/figures.json" README.md <<'PY'
import json, sys
fig = json.load(open(sys.argv[1]))
lines = ["<!-- figures:begin (tools/figures.sh --write; do not edit by hand) -->", "",
         "| skill | evaluation (`eval_policy`, trials, seed) | success | falls | mean contact error | checkpoint sha256 |",
         "|---|---|---|---|---|---|"]
for skill, p in sorted(fig["policies"].items()):
    starts = p.get("reference_starts", 0)
    starts = f", {100 * starts:.0f} % clip starts" if starts else ""
    if p.get("action_smoothing", 0):
        starts += f", action smoothing {p['action_smoothing']:g}"
    lines.append(f"| {skill} | {p['scene']}, {p['trials']} trials, seed {p['seed']}{starts} | "
                 f"{100 * p['success_rate']:.0f} % | {100 * p['fall_rate']:.0f} % | "
                 f"{p['contact_error']:.2f} m | `{p['checkpoint_sha256'][:12]}` |")
s = fig["story"]
lines += ["", f"Main story (`{s['script']}`): {s['succeeded']} of {s['keyframes']} keyframes succeed "
          f"over seeds 0–{s['seeds'] - 1} (per seed: "
          + ", ".join(f"{x['succeeded']}/{x['keyframes']}" for x in s["per_seed"]) + ")."]
for name, r in sorted(fig["retrieval"].items()):
    lines.append(f"Caption retrieval, {name} paraphrases: {r['correct']}/{r['total']}.")
paper = {"simple": 74.3, "mid": 42.2, "hard": 31.5}
lines += ["", f"Stories per difficulty (SIMS Table 2 protocol, `{fig['stories']['command']}`; "
          "the paper's full method for scale):", "",
          "| difficulty | stories | keyframe success | SIMS paper | contact error | foot sliding | FID | APD |",
          "|---|---|---|---|---|---|---|---|"]
for d in ("simple", "mid", "hard"):
    x = fig["stories"]["per_difficulty"].get(d)
    if not x:
        continue
    lines.append(f"| {d} | {x['stories']} | {100 * x['success_rate']:.1f} % | {paper[d]} % | "
                 f"{x['contact_error']:.2f} m | {x['foot_sliding_m_per_s']:.2f} m/s | "
                 f"{x.get('fid', float('nan')):.2f} | {x['apd']:.2f} |")
per_skill = fig["stories"].get("per_skill", {})
if per_skill:
    lines += ["", "Keyframes per skill over those stories: " + ", ".join(
        f"{k} {x['succeeded']}/{x['keyframes']} ({x['falls']} falls)"
        for k, x in sorted(per_skill.items())) + "."]
ref_slide = fig["stories"].get("reference_foot_sliding_m_per_s")
if ref_slide is not None:
    lines += ["", f"Foot sliding of the demonstration clips by the same measure: {ref_slide:.3f} m/s."]
lines += ["", "<!-- figures:end -->"]
text = open(sys.argv[2]).read()
begin, end = text.find("<!-- figures:begin"), text.find("<!-- figures:end -->")
if begin < 0 or end < 0:
    sys.exit("README.md: expected a <!-- figures:begin --> ... <!-- figures:end --> block")
text = text[:begin] + "\n".join(lines) + text[end + len("<!-- figures:end -->"):]
open(sys.argv[2], "w").write(text)
PY
  step "wrote assets/policies/*/eval.json and the README figures block"
fi
