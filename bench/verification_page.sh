#!/bin/sh
# Regenerates the table of docs/verification.md from `tribo validate --json` (the test
# `verification_page_has_every_row_of_tribo_validate` in crates/tribo-cli/tests/docs.rs writes it
# when TRIBO_REGENERATE_DOCS is set, and otherwise checks that the page is current).
set -eu
cd "$(dirname "$0")/.."
TRIBO_REGENERATE_DOCS=1 cargo test --release -p tribo-cli --test docs \
    verification_page_has_every_row_of_tribo_validate -- --exact
echo "docs/verification.md regenerated: $(grep -c '^| [0-9]' docs/verification.md) rows"
