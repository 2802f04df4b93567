#!/usr/bin/env bash
# The bash completion (packaging/bash-completion/pvtap) driven as bash drives it: every option
# of each subcommand's --help is offered, option values, serial devices, capture files.
# Usage: check_completion.sh PVTAP COMPLETION_FILE
set -uo pipefail
pvtap=$1
completion=$2
failures=0

# shellcheck source=/dev/null
source /usr/share/bash-completion/bash_completion
# shellcheck source=packaging/bash-completion/pvtap
source "$completion"

# The completions bash would offer for the command line "$@" (the last word being completed;
# the first is the program, whose --help the completion reads).
complete_line() {
    COMP_WORDS=("$@")
    COMP_CWORD=$(($# - 1))
    COMP_LINE="$*"
    COMP_POINT=${#COMP_LINE}
    COMPREPLY=()
    _pvtap pvtap "${COMP_WORDS[COMP_CWORD]}" "${COMP_WORDS[COMP_CWORD - 1]}" 2>/dev/null
    printf '%s\n' "${COMPREPLY[@]}" | sort -u
}

# The long options of "pvtap SUBCOMMAND --help", from its option lines.
help_options() {
    "$pvtap" "$1" --help | sed -n 's/^ \{2,12\}\(-[a-z], *\)\?\(--[a-z][a-z-]*\).*/\2/p' | sort -u
}

expect_same() {
    local what=$1 expected=$2 got=$3
    if [[ "$expected" != "$got" ]]; then
        echo "FAIL: $what"
        diff <(echo "$expected") <(echo "$got") | sed 's/^/  /'
        failures=$((failures + 1))
    else
        echo "ok: $what"
    fi
}

expect_contains() {
    local what=$1 needle=$2 got=$3
    if grep -qxF -- "$needle" <<<"$got"; then
        echo "ok: $what"
    else
        echo "FAIL: $what: no '$needle' in: $(echo $got)"
        failures=$((failures + 1))
    fi
}

# The subcommands of "pvtap --help", from its Subcommands section.
subcommands=$("$pvtap" --help | sed -n '/^Subcommands:/,/^$/s/^  \([a-z][a-z-]*\) .*/\1/p')
expect_same "subcommands are those of pvtap --help" \
    "$(printf '%s\n' --help --version $subcommands | sort)" "$(complete_line pvtap '')"
for subcommand in $subcommands; do
    options=$(help_options "$subcommand")
    if [[ $(wc -l <<<"$options") -lt 2 ]]; then
        echo "FAIL: too few options parsed from pvtap $subcommand --help: $(echo $options)"
        failures=$((failures + 1))
    fi
    expect_same "$subcommand options are those of its --help" "$options" \
        "$(complete_line "$pvtap" "$subcommand" --)"
done
expect_same "--format values" "$(printf '%s\n' csv jsonl text)" \
    "$(complete_line "$pvtap" audit --format '')"
expect_same "--values-format values" "$(printf '%s\n' csv influx jsonl)" \
    "$(complete_line "$pvtap" audit --values-format '')"
expect_same "sniff --values-format values" "$(printf '%s\n' csv influx jsonl)" \
    "$(complete_line "$pvtap" sniff --values-format '')"
expect_same "--dialect values" "$(printf '%s\n' ascii auto gsl hybrid modbus)" \
    "$(complete_line "$pvtap" sniff --dialect '')"
expect_same "glossary --format values" "$(printf '%s\n' jsonl markdown text)" \
    "$(complete_line "$pvtap" glossary --format '')"
expect_same "--gsl-ids values" "$(printf '%s\n' decimal hex)" \
    "$(complete_line "$pvtap" audit --gsl-ids '')"
expect_same "sniff --baud offers auto" "auto" "$(complete_line "$pvtap" sniff --baud a)"
expect_same "audit --baud has no auto" "" "$(complete_line "$pvtap" audit --baud a)"
expect_same "nothing is guessed for --timeout" "" "$(complete_line "$pvtap" audit --timeout '')"
expect_same "--fail-on's values" "$(printf '%s\n' empty errors)" \
    "$(complete_line "$pvtap" audit --fail-on '')"
expect_same "--mqtt offers the two schemes" "$(printf '%s\n' mqtt:// mqtts://)" \
    "$(complete_line "$pvtap" sniff --mqtt '')"
expect_same "--parity values" "$(printf '%s\n' even none odd)" \
    "$(complete_line "$pvtap" sniff --device /dev/ttyS0 --parity '')"

# Serial devices: what the system has, and the ports of PVTAP_SERIAL_PORTS.
export PVTAP_SERIAL_PORTS=/dev/pts/77:/dev/pvtap-test-port
devices=$(complete_line "$pvtap" sniff --device '')
expect_contains "--device offers PVTAP_SERIAL_PORTS" /dev/pvtap-test-port "$devices"
for tty in /dev/ttyS0 /dev/ttyUSB0; do
    [[ -e $tty ]] && expect_contains "--device offers $tty" "$tty" "$devices"
done
unset PVTAP_SERIAL_PORTS

# Capture files (and folders) for audit's FILEs, not other files.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
mkdir "$scratch/site"
touch "$scratch/a.pcap" "$scratch/b.pcapng" "$scratch/notes.txt" "$scratch/site.toml" \
    "$scratch/ca.crt"
cd "$scratch" || exit 1
expect_same "audit FILE offers captures and folders" "$(printf '%s\n' a.pcap b.pcapng site)" \
    "$(complete_line "$pvtap" audit --summary-only '')"
expect_same "--mqtt-ca offers certificates and folders" "$(printf '%s\n' ca.crt site)" \
    "$(complete_line "$pvtap" sniff --mqtt-ca '')"
expect_same "--map offers TOML files and folders" "$(printf '%s\n' site site.toml)" \
    "$(complete_line "$pvtap" audit --map '')"

if ((failures > 0)); then
    echo "$failures completion check(s) failed"
    exit 1
fi
echo "all completion checks hold"
