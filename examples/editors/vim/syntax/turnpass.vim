" Vim syntax for Okuma OSP and Fanuc-compatible lathe programs (turnpass).
"
" For editors that do not colour with the language server's semantic tokens (Vim, Neovim
" before 0.9): codes, addresses apart from their values, sequence and program names,
" keywords, variables, comments. The server's tokens say more (which `N` a `P` names, a
" block that does not parse); this file only reads the characters.

if exists("b:current_syntax")
  finish
endif

syntax case match

" Comments: `( … )` in both dialects, `; …` to the end of the line (Fanuc).
syntax region turnpassComment start=/(/ end=/)/ oneline
syntax match turnpassComment /;.*$/

" Tape marks, the OSP file header, block delete.
syntax match turnpassTape /^\s*%.*$/
syntax match turnpassHeader /^\$\S*%/
syntax match turnpassBlockDelete /^\s*\/\d\?/

" Sequence names (`N20`, `NAT00`) and program names (`O1234`, `OSUB`, `:0100`).
syntax match turnpassSequence /\<N[0-9A-Z]\+\>/
syntax match turnpassProgram /^\s*[O:][0-9A-Z]\+/

" G and M codes.
syntax match turnpassGCode /\<G\d\+\(\.\d\)\?/
syntax match turnpassMCode /\<M\d\+/

" Keywords of both dialects' macro languages.
syntax keyword turnpassKeyword IF GOTO THEN WHILE DO END CALL RTS MODIN MODOUT
syntax keyword turnpassOperator EQ NE GT GE LT LE AND OR XOR MOD

" Variables: Fanuc `#100`, OSP `V1`, `VC12`, `VTOFX[1]`.
syntax match turnpassVariable /#\d\+/
syntax match turnpassVariable /\<V[A-Z]*\d*\(\[\)\@=/
syntax match turnpassVariable /\<VC\?\d\+\>/

" An address and its value: `X20.`, `Z-5`, `F0.2`, OSP `XA=60`, `X=VC1*2`.
syntax match turnpassAddress /\<[A-FH-LPQR-Z][A-Z]\?\ze\s*=\?\s*[-+.0-9\[#A-Z]/ nextgroup=turnpassNumber
syntax match turnpassNumber /[-+]\?\d*\.\?\d\+\.\?/ contained

highlight default link turnpassComment Comment
highlight default link turnpassTape PreProc
highlight default link turnpassHeader PreProc
highlight default link turnpassBlockDelete PreProc
highlight default link turnpassSequence Label
highlight default link turnpassProgram Function
highlight default link turnpassGCode Statement
highlight default link turnpassMCode Special
highlight default link turnpassKeyword Keyword
highlight default link turnpassOperator Operator
highlight default link turnpassVariable Identifier
highlight default link turnpassAddress Type
highlight default link turnpassNumber Number

let b:current_syntax = "turnpass"
