#!/usr/bin/env bash
# Debian packages that the set-up (make, python3-venv), the handouts (TeX, pdftoppm) and the
# browser test (Chromium, MathJax) and the exported MATLAB files' test (GNU Octave: 40 s,
# ~285 MB with --no-install-recommends, measured on Debian 12) need. Installs only what is missing; needs root (or sudo)
# and apt-get. Elsewhere it says what to install.
#   PYTHON=python3 bash scripts/system-deps.sh     (run by `make setup`, or by hand before it)
set -euo pipefail
PYTHON="${PYTHON:-python3}"
PKGS=(make texlive-latex-base texlive-latex-recommended texlive-latex-extra latexmk poppler-utils
      chromium libjs-mathjax octave)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# `python3 -m venv` needs ensurepip, which Debian and Ubuntu ship apart, in python3-venv.
if ! "$PYTHON" -c "import ensurepip, venv" >/dev/null 2>&1; then
  missing+=(python3-venv)
fi
[ ${#missing[@]} -eq 0 ] && exit 0
if ! command -v apt-get >/dev/null 2>&1; then
  echo "note: install ${missing[*]} (python3-venv and make for the set-up; the rest for PDF" \
       "handouts and the browser test)" >&2; exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "note: run as root: apt-get install --no-install-recommends ${missing[*]}" >&2; exit 0
  fi
fi
echo "installing Debian packages: ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q >/dev/null
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}" >/dev/null
