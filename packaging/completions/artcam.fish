# SPDX-License-Identifier: Apache-2.0
# fish completion for artcam(1), installed as /usr/share/fish/vendor_completions.d/artcam.fish.
# Commands, bench's and lens's sub-commands, each page's options and their values, preset names
# and a preset's parameters, all asked of artcam itself at completion time (a page's --help, and
# `artcam preset list`), so they follow the parsers and the effects table without an edit here.
# tests/app/test_cli_completions.cpp runs it through `fish -c 'complete -C …'`.

# The words that name the help page the command line is on: "warp", "bench fit", "lens camera".
function __artcam_page
    set -l words (commandline -opc)
    set -l command ''
    for w in $words[2..-1]
        if string match -q -- '-*' $w
            continue
        end
        if test -z "$command"
            set command $w
            continue
        end
        switch $command
            case bench
                contains -- $w render fit effects; and echo "bench $w"; and return
            case lens
                contains -- $w search camera; and echo "lens $w"; and return
        end
        break
    end
    test "$command" = bench; and echo "bench render"; and return
    echo $command
end

function __artcam_complete
    set -l artcam (commandline -opc)[1]
    set -l words (commandline -opc)
    set -l current (commandline -ct)
    set -l page (__artcam_page)
    if test -z "$page"
        printf '%s\n' fit map warp batch info bench render preset compose export export-map lens \
            insert sample stereo unfold help --help --version
        return
    end
    set -l page_words (string split ' ' -- $page)
    # A sub-command right after bench or lens.
    if test (count $words) -eq 2; and not string match -q -- '-*' $current
        switch $page_words[1]
            case bench
                printf '%s\n' render fit effects
                return
            case lens
                printf '%s\n' search camera
                return
            case preset
                $artcam preset list 2>/dev/null | string match -r -- '^  [^ ]+' | string trim
                echo list
                return
        end
    end
    # The value of an option whose help spells its choices ("--edge transparent|extend|black").
    set -l previous $words[-1]
    if string match -q -- '--*' $previous
        set -l values ($artcam $page_words --help 2>/dev/null |
            string match -ar -- "$previous [a-z0-9.]+(?:\|[a-z0-9.]+)+" |
            string split -f2 ' ' | string split '|' | sort -u)
        if test (count $values) -gt 0
            printf '%s\n' $values
            return
        end
    end
    if string match -q -- '-*' $current
        # Every option a page's help names, and a preset's parameters as options.
        $artcam $page_words --help 2>/dev/null |
            string match -ar -- '(?<![A-Za-z0-9-])--?[A-Za-z][A-Za-z0-9-]*' | sort -u
        if test $page_words[1] = preset; and test (count $words) -ge 3
            $artcam preset list 2>/dev/null | awk -v want=$words[3] '
                /^  [^ ]/ { name = $1; next }
                name == want { for (i = 1; i <= NF; i++) if (split($i, kv, "=") == 2) print "--" kv[1] }'
        end
        return
    end
    __fish_complete_path $current
end

complete -c artcam -f -a '(__artcam_complete)'
