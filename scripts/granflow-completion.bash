# SPDX-License-Identifier: MIT
# Bash completion of granflow (installed as
# share/bash-completion/completions/granflow). The commands come from
# `granflow help`, each command's options from `granflow CMD --help`, the
# configuration keys of --set from `granflow config`, the measurements of
# analyze from `granflow analyze --list`: nothing here goes stale.
_granflow() {
    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]}
    local gf=${COMP_WORDS[0]}
    COMPREPLY=()
    if [ "$COMP_CWORD" -eq 1 ]; then
        local cmds
        cmds=$("$gf" help 2>/dev/null | sed -n '/^commands:/,/^$/s/^  \([a-z]\+\) .*/\1/p')
        COMPREPLY=($(compgen -W "$cmds --help --version" -- "$cur"))
        return
    fi
    local cmd=${COMP_WORDS[1]}
    case $prev in
        -s|--set)
            local keys
            keys=$("$gf" config 2>/dev/null | awk '/^\[/{ gsub(/[][]/, ""); s = $0; next }
                                                 /^[a-z_0-9]+ *=/{ print s "." $1 "=" }')
            compopt -o nospace 2>/dev/null
            COMPREPLY=($(compgen -W "$keys" -- "$cur"))
            return ;;
        -o|--output|--resume|--config)
            COMPREPLY=($(compgen -f -- "$cur"))
            compopt -o filenames 2>/dev/null
            return ;;
        --colour|--color) COMPREPLY=($(compgen -W "layer phi phi-raw" -- "$cur")); return ;;
        --format) COMPREPLY=($(compgen -W "png svg pdf" -- "$cur")); return ;;
        --times|--scale|--panels|--particles|--warmup|--window|--timestep|--runs) return ;;
    esac
    if [ "$cmd" = help ]; then
        COMPREPLY=($(compgen -W "$("$gf" help 2>/dev/null | sed -n '/^commands:/,/^$/s/^  \([a-z]\+\) .*/\1/p')" -- "$cur"))
        return
    fi
    if [[ $cur == -* ]]; then
        local opts
        # Options from the synopsis and the options section (not the prose).
        opts=$("$gf" "$cmd" --help 2>/dev/null |
               awk 'BEGIN { h = 1 } h && (NR == 1 || /^[ \t]/ || /^usage:/) { print; next } { h = 0 } /^options:/ { o = 1 } o' |
               grep -oE '(^|[ ,[|(])--?[a-zA-Z][a-z-]*' | sed 's/^[ ,[|(]//' | sort -u)
        COMPREPLY=($(compgen -W "$opts" -- "$cur"))
        return
    fi
    local names=""
    [ "$cmd" = analyze ] && [ "$COMP_CWORD" -eq 2 ] &&
        names=$("$gf" analyze --list 2>/dev/null | sed -n 's/^  \([a-z_0-9]\+\) .*/\1/p')
    COMPREPLY=($(compgen -W "$names" -- "$cur") $(compgen -f -- "$cur"))
    compopt -o filenames 2>/dev/null
}
complete -F _granflow granflow
