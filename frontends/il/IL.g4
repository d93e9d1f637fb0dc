// IEC 61131-3 Instruction List bodies: the parser grammar.
//
// An IL file declares its POUs like Structured Text (the ST grammar parses
// the declarations); only the bodies are instruction lists, parsed here.
// The tokens are ST's (one hand-written lexer, see StLexer.h), with line
// ends significant. Operands are kept as token runs: the frontend parses
// each with the ST expression parser, so literals and variable accesses
// mean exactly what they mean in ST.
parser grammar IL;

options { tokenVocab = ST; }

ilBody : (ilLine | EOL)* EOF ;

ilLine
  : labelDef EOL* instruction
  | labelDef
  | instruction
  ;

labelDef : name=IDENT COLON ;

instruction
  : op=opName target=IDENT LPAREN EOL* (callArg (COMMA EOL* callArg)*)? EOL* RPAREN # callWithArgs
  | op=opName LPAREN EOL* (callArg (COMMA EOL* callArg)*)? EOL* RPAREN              # formalCall
  | op=opName LPAREN operand?                                                      # deferred
  | RPAREN                                                                         # closeParen
  | op=opName (operand (COMMA operand)*)?                                          # simple
  ;

// IL operators: mostly plain names (LD, ST, ANDN, CAL, JMPC, RET...), some
// spelled like ST keywords.
opName : IDENT | AND | OR | XOR | NOT | MOD | JMP | AMP IDENT? ;

callArg
  : NOT? name=IDENT (ASSIGN | OUTPUT_ASSIGN) operand?
  ;

operand : (~(EOL | COMMA | LPAREN | RPAREN | COLON | EOF))+ ;
