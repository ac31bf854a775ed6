# Sourced by the bench scripts that compare two recordings of one run.
# same_dataset A B: true when the datasets in folders A and B are byte-identical
# in what a seed decides (trials/, manifest.csv, dataset-info.csv,
# features.csv); otherwise names the first difference on stderr.
same_dataset() {
  local f
  for f in manifest.csv dataset-info.csv features.csv; do
    cmp -s "$1/$f" "$2/$f" || { echo "$f differs between $1 and $2" >&2; return 1; }
  done
  diff -rq "$1/trials" "$2/trials" >/dev/null || { echo "trials/ differ between $1 and $2" >&2; return 1; }
}
