#!/usr/bin/env bash
# Installs the Debian packages bonered_alg uses, if missing and if this shell can (root + apt).
#   singular  -- the default Groebner engine (GPL; driven as a separate program)
#   latex     -- (with --latex) pdflatex + latexmk for `make report`
set -euo pipefail
want=()
command -v Singular >/dev/null 2>&1 || want+=(singular)
if [[ "${1:-}" == "--latex" ]]; then
  command -v latexmk >/dev/null 2>&1 || want+=(latexmk)
  command -v pdflatex >/dev/null 2>&1 || want+=(texlive-latex-base texlive-latex-recommended)
fi
[[ ${#want[@]} -eq 0 ]] && exit 0
if [[ $(id -u) -eq 0 ]] && command -v apt-get >/dev/null 2>&1; then
  echo "installing Debian packages: ${want[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${want[@]}" >/dev/null
else
  echo "note: missing ${want[*]}; install them with your package manager" \
       "(Debian: sudo apt-get install --no-install-recommends ${want[*]})." >&2
  echo "note: without Singular the sympy engine is used, which is far slower" \
       "(minutes to hours per elimination; see README)." >&2
fi
