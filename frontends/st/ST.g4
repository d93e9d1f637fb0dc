// IEC 61131-3 (3rd edition) Structured Text: the parser grammar.
//
// Tokens come from the hand-written lexer in StLexer.cpp (keywords are
// case-insensitive, comments nest, typed and duration literals are single
// tokens, pragmas go to a hidden channel), so this file declares token types
// only. Constructs netlift refuses (object orientation, pointers, SFC,
// actions) are still parsed here, loosely, so that the refusal can name the
// construct at its own location instead of reporting a syntax error.
parser grammar ST;

tokens {
  // Structure
  PROGRAM, END_PROGRAM, FUNCTION_BLOCK, END_FUNCTION_BLOCK, FUNCTION,
  END_FUNCTION, TYPE, END_TYPE, STRUCT, END_STRUCT, UNION, END_UNION,
  CONFIGURATION, END_CONFIGURATION, RESOURCE, END_RESOURCE, ON, TASK,
  WITH, VAR, VAR_INPUT, VAR_OUTPUT, VAR_IN_OUT, VAR_EXTERNAL, VAR_GLOBAL,
  VAR_TEMP, VAR_ACCESS, VAR_CONFIG, VAR_STAT, VAR_INST, END_VAR, CONSTANT,
  RETAIN, NON_RETAIN, PERSISTENT, AT, ARRAY, OF, STRING_KW, WSTRING_KW,
  POINTER, REFERENCE, TO, REF_TO,
  // Object orientation and other refused structure
  METHOD, END_METHOD, PROPERTY, END_PROPERTY, END_GET, END_SET, INTERFACE,
  END_INTERFACE,
  EXTENDS, IMPLEMENTS, ACTION, END_ACTION, ACTIONS, END_ACTIONS, CLASS,
  END_CLASS, NAMESPACE, END_NAMESPACE,
  INITIAL_STEP, STEP, END_STEP, TRANSITION, END_TRANSITION, FROM,
  ABSTRACT, FINAL, PUBLIC, PRIVATE, PROTECTED, INTERNAL, OVERRIDE,
  // Statements
  IF, THEN, ELSIF, ELSE, END_IF, CASE, END_CASE, FOR, BY, DO, END_FOR,
  WHILE, END_WHILE, REPEAT, UNTIL, END_REPEAT, EXIT, CONTINUE, RETURN,
  JMP,
  // Operators
  OR, XOR, AND, NOT, MOD, AND_THEN, OR_ELSE, TRUE, FALSE,
  ASSIGN, OUTPUT_ASSIGN, REF_ASSIGN, ATTEMPT_ASSIGN, SET_ASSIGN, RESET_ASSIGN, EQ, NE, LT,
  LE, GT, GE, PLUS, MINUS, STAR, SLASH, POWER, AMP, CARET, LPAREN, RPAREN,
  LBRACKET, RBRACKET, COMMA, SEMI, COLON, DOT, DOTDOT, HASH,
  // Literals and names
  IDENT, INTEGER, REAL_LIT, DURATION, TOD_LIT, DATE_LIT, DT_LIT, STRING_LIT,
  WSTRING_LIT, DIRECT,
  // matiec's `{{ C code }}`, one token
  EMBEDDED_C,
  // Line ends, emitted only when lexing Instruction List bodies (IL.g4)
  EOL
}

// ---------------------------------------------------------------- units

// A `;` between elements (after a comment, as TwinCAT exports write one) is
// empty.
compilationUnit : (libraryElement | SEMI)* EOF ;

// One expression alone (IL operands, --ranges values).
expressionOnly : expression EOF ;

// An initial value alone (IEC 61499 InitialValue attributes).
initializerOnly : initializer EOF ;

// A POU body alone (the ST bodies of PLCopen XML).
statementsOnly : bodyStatementList EOF ;

// An IEC 61499 ST algorithm: 4diac lets VAR_TEMP blocks open it.
algorithmBody : varBlock* bodyStatementList EOF ;

// A METHOD alone (an IEC 61499 basic FB's method, as 4diac IDE 3 writes it).
methodOnly : methodDecl EOF ;

// A method's body alone (4diac IDE 3 keeps the name and the result type
// apart): its variable blocks, then its statements.
methodBodyOnly : pouVarBlock* body=bodyStatementList EOF ;

// Declarations alone (a long VAR block parsed in groups).
varDeclsOnly : varDecl* EOF ;

libraryElement
  : programDecl
  | functionBlockDecl
  | functionDecl
  | typeDecl
  | configurationDecl
  | globalVarBlock
  | classDecl
  | interfaceDecl
  | actionsBlock
  | refusedElement
  ;

// IEC 61131-3 3rd edition CLASS: a function block without a body, used
// through its methods.
classDecl
  : CLASS accessModifier* name=IDENT
    (EXTENDS ext=qualifiedName)? (IMPLEMENTS qualifiedName (COMMA qualifiedName)*)?
    pouVarBlock* fbMember* END_CLASS
  ;

// An INTERFACE: the methods and properties (without bodies) of the
// blocks that IMPLEMENT it.
interfaceDecl
  : INTERFACE name=IDENT (EXTENDS qualifiedName (COMMA qualifiedName)*)?
    (methodDecl | propertyDecl)* END_INTERFACE
  ;

// Actions written after the POU they belong to (`ACTIONS [pou] ACTION a
// ... END_ACTION END_ACTIONS`, as RuSTy and CODESYS exports write them).
actionsBlock : ACTIONS owner=ident? sfcAction* END_ACTIONS ;

// Elements netlift refuses by name; their body is skipped token by token.
refusedElement
  : kw=NAMESPACE (~END_NAMESPACE)* END_NAMESPACE
  | kw=ACTION (~END_ACTION)* END_ACTION
  | kw=METHOD (~END_METHOD)* END_METHOD
  | kw=PROPERTY (~END_PROPERTY)* END_PROPERTY
  ;

programDecl
  : PROGRAM name=IDENT pouVarBlock* fbMember* body=bodyStatementList fbMember*
    END_PROGRAM
  ;

functionBlockDecl
  : FUNCTION_BLOCK accessModifier* name=IDENT
    (EXTENDS ext=qualifiedName)? (IMPLEMENTS qualifiedName (COMMA qualifiedName)*)?
    pouVarBlock* fbMember* body=bodyStatementList fbMember* END_FUNCTION_BLOCK
  ;

accessModifier
  : ABSTRACT | FINAL | PUBLIC | PRIVATE | PROTECTED | INTERNAL | OVERRIDE ;

// A PROPERTY (CODESYS, TwinCAT): a GET and a SET accessor, each a method
// (`GET ... END_GET`, `SET ... END_SET`; the TwinCAT reader writes them so).
propertyDecl
  : PROPERTY accessModifier* name=ident COLON type=typeSpec0 SEMI?
    propertyAccessor* END_PROPERTY SEMI?
  ;

propertyAccessor
  : kw=IDENT accessModifier* pouVarBlock* body=bodyStatementList
    end=(END_GET | END_SET) SEMI?
  ;

// A METHOD of a function block or program (IEC 61131-3 3rd edition, 6.6.5):
// a function that runs on the instance, whose variables it sees.
methodDecl
  : METHOD accessModifier* name=ident (COLON result=typeSpec)? SEMI?
    pouVarBlock* body=bodyStatementList END_METHOD SEMI?
  ;

// Methods, properties, actions and SFC elements inside a POU.
fbMember
  : methodDecl
  | propertyDecl
  | sfcAction
  | sfcStep
  | sfcTransition
  ;

// Sequential Function Chart (IEC 61131-3 3rd edition, 6.7). An action
// association's arguments are read as expressions: the qualifier, its
// time and the indicators are told apart when the chart is built.
sfcStep
  : kw=(INITIAL_STEP | STEP) name=ident COLON actionAssociation* END_STEP SEMI?
  ;

actionAssociation
  : action=ident LPAREN (expression (COMMA expression)*)? RPAREN SEMI
  ;

sfcTransition
  : kw=TRANSITION name=ident?
    (LPAREN priorityKw=IDENT ASSIGN priority=INTEGER RPAREN)?
    FROM from=sfcStepSet TO to=sfcStepSet
    (ASSIGN cond=expression SEMI | il=COLON (~END_TRANSITION)*)
    END_TRANSITION SEMI?
  ;

sfcStepSet : ident | LPAREN ident (COMMA ident)* RPAREN ;

sfcAction
  : kw=ACTION name=ident COLON? body=statementList END_ACTION SEMI?
  ;

functionDecl
  : FUNCTION accessModifier* name=IDENT (COLON result=typeSpec)? SEMI?
    pouVarBlock* body=bodyStatementList END_FUNCTION
  ;

qualifiedName : ident (DOT ident)* ;

// Words IEC reserves only in some places (SFC, resources, OOP) are ordinary
// names everywhere else: real programs call variables `step` or `on`.
ident
  : IDENT | ON | STEP | FROM | ACTION | ACTIONS | CLASS | METHOD | PROPERTY
  | INTERFACE
  | NAMESPACE | ABSTRACT | FINAL | PUBLIC | PRIVATE | PROTECTED | INTERNAL
  | OVERRIDE | POINTER | REFERENCE | TRANSITION
  ;

// ---------------------------------------------------------------- types

// `TYPE INTERNAL ...` (CODESYS, TwinCAT: visible in its library only).
typeDecl : TYPE access=(INTERNAL | PUBLIC)? typeDefinition* END_TYPE ;

typeDefinition
  : name=ident (EXTENDS ext=qualifiedName)? COLON typeSpec SEMI?
  ;

typeSpec
  : elem=typeSpec0 (ASSIGN (bare=bareArrayInit | init=initializer))?
  ;

// CODESYS V2 and TwinCAT 2 write an array's initial values without the
// brackets: `a : ARRAY[1..3] OF INT := 1, 2, 3;`.
bareArrayInit : arrayInitElem (COMMA arrayInitElem)+ ;

typeSpec0
  : ARRAY LBRACKET arrayDim (COMMA arrayDim)* RBRACKET OF elem=typeSpec0   # arrayType
  // `ARRAY[1..2] OF FB_Axis[(nId := 1), (nId := 2)]`: each element's
  // FB_init arguments, in order (TwinCAT).
  | ARRAY LBRACKET arrayDim (COMMA arrayDim)* RBRACKET OF base=IDENT
    LBRACKET elementArgs (COMMA elementArgs)* RBRACKET                    # instanceArrayType
  | STRUCT (structField)* END_STRUCT                                      # structType
  | UNION (structField)* END_UNION                                        # unionType
  | (POINTER TO | REFERENCE TO | REF_TO) typeSpec0                        # pointerType
  | base=IDENT? LPAREN enumValue (COMMA enumValue)* RPAREN after=IDENT?   # enumType
  | base=IDENT LPAREN subrange RPAREN                                     # subrangeType
  // `fb : FB_Axis(1, 2)`: an instance and its FB_init's arguments in order
  // (TwinCAT).
  | base=IDENT LPAREN expression (COMMA expression)* RPAREN               # instanceArgsType
  | (STRING_KW | WSTRING_KW) ((LBRACKET | LPAREN) length=expression (RBRACKET | RPAREN))? # stringType
  | qualifiedName                                                         # namedType
  ;

enumValue : name=ident (ASSIGN value=expression)? ;

elementArgs : LPAREN elementArg (COMMA elementArg)* RPAREN ;
elementArg : (name=ident ASSIGN)? value=expression ;

subrange : lo=expression DOTDOT hi=expression ;

// `*`: the bounds of the array a VAR_IN_OUT is given (IEC 61131-3 3rd
// edition, CODESYS V3, TwinCAT 3).
arrayDim : subrange | STAR ;

structField
  : ident (COMMA ident)* (AT DIRECT)? COLON typeSpec SEMI
  ;

// An initial value: an expression, an array initialiser `[1, 2, 3(0)]` or
// a structure initialiser `(x := 1, y := 2)`.
initializer
  : LBRACKET arrayInitElem (COMMA arrayInitElem)* RBRACKET      # arrayInit
  | LPAREN fieldInit (COMMA fieldInit)* RPAREN                  # structInit
  | expression                                                  # exprInit
  ;

arrayInitElem
  : count=INTEGER LPAREN initializer? RPAREN
  | initializer
  ;

fieldInit : ident ASSIGN initializer ;

// ---------------------------------------------------------------- variables

pouVarBlock : varBlock ;

varBlock
  : kind=(VAR | VAR_INPUT | VAR_OUTPUT | VAR_IN_OUT | VAR_EXTERNAL | VAR_GLOBAL
          | VAR_TEMP | VAR_CONFIG | VAR_STAT | VAR_INST)
    varQualifier* varDecl* END_VAR
  | kind=VAR_ACCESS accessDecl* END_VAR
  ;

globalVarBlock : varBlock ;

// INTERNAL (CODESYS, TwinCAT: visible in its library only) changes nothing
// in one design.
varQualifier : CONSTANT | RETAIN | NON_RETAIN | PERSISTENT | INTERNAL ;

varDecl
  : ident (COMMA ident)* (AT DIRECT)? COLON typeSpec edge=IDENT? SEMI
  | AT DIRECT COLON typeSpec SEMI
  | accessPath COLON typeSpec SEMI
  ;

// A VAR_ACCESS entry: `Level : C.R.inst.level : INT READ_ONLY;`.
accessDecl
  : accessName=ident COLON accessTarget COLON typeSpec direction=IDENT? SEMI
  ;
accessTarget : ident (DOT ident)* ;

// VAR_CONFIG and VAR_ACCESS entries (refused; parsed to name them).
accessPath : ident (DOT ident)+ (AT DIRECT)? ;

// ---------------------------------------------------------------- config

configurationDecl
  : CONFIGURATION name=IDENT configItem* END_CONFIGURATION
  ;

configItem
  : varBlock
  | resourceDecl
  | taskDecl
  | programConfig
  ;

resourceDecl
  : RESOURCE name=IDENT (ON target=IDENT)? resourceItem* END_RESOURCE
  ;

resourceItem : varBlock | taskDecl | programConfig ;

taskDecl
  : TASK name=IDENT (LPAREN taskParam (COMMA taskParam)* RPAREN)? SEMI
  ;

taskParam : ident ASSIGN expression ;

programConfig
  : PROGRAM accessModifier* inst=IDENT (WITH task=IDENT)? COLON type=IDENT
    (LPAREN (callArg (COMMA callArg)*)? RPAREN)? SEMI
  ;

// ---------------------------------------------------------------- statements

statementList : statement* ;

// A POU body: statements, and the labels CODESYS lets JMP go to (at the
// body's top level only; inside CASE an `IDENT :` is a case label).
bodyStatementList : (bodyLabel | statement)* ;

bodyLabel : name=ident COLON ;

statement
  : SEMI                                                        # emptyStmt
  | target=variable ASSIGN value=expression SEMI                # assignStmt
  | target=variable op=(REF_ASSIGN | ATTEMPT_ASSIGN) value=expression SEMI # refAssignStmt
  | setOrReset+ value=expression SEMI                           # setResetStmt
  | callee=variable LPAREN (callArg (COMMA callArg)*)? RPAREN callSuffix* SEMI # callStmt
  | IF cond=expression THEN statementList
    (elsifPart)* (ELSE elseBody=statementList)? END_IF SEMI?    # ifStmt
  | CASE sel=expression OF caseArm* (ELSE elseBody=statementList)? END_CASE SEMI? # caseStmt
  | FOR var=ident ASSIGN from=expression TO to=expression (BY by=expression)? DO
    statementList END_FOR SEMI?                                 # forStmt
  | WHILE cond=expression DO statementList END_WHILE SEMI?      # whileStmt
  | REPEAT statementList UNTIL cond=expression END_REPEAT SEMI? # repeatStmt
  | EXIT SEMI                                                   # exitStmt
  | CONTINUE SEMI                                               # continueStmt
  | RETURN SEMI                                                 # returnStmt
  | JMP IDENT SEMI                                              # jumpStmt
  | EMBEDDED_C                                                  # embeddedCStmt
  ;

// CODESYS's and TwinCAT's set and reset assignments `x S= c;`, `x R= c;`,
// chained `x S= y R= c;` (each target from the one operand at the end).
// The lexer reads `S=` as one token only right after a variable.
setOrReset : target=variable op=(SET_ASSIGN | RESET_ASSIGN) ;

elsifPart : ELSIF cond=expression THEN statementList ;

caseArm : caseLabel (COMMA caseLabel)* COLON statementList ;

caseLabel
  : lo=expression (DOTDOT hi=expression)?
  ;

// A method called on what a call returns (`log.Info('x').Send()`, through
// a pointer: `p()^.M()`).
callSuffix
  : deref=CARET? DOT name=ident LPAREN (callArg (COMMA callArg)*)? RPAREN
  ;

callArg
  : name=ident ASSIGN value=expression        # namedInput
  | NOT? name=ident OUTPUT_ASSIGN target=variable # namedOutput
  | value=expression                          # positionalArg
  ;

// ---------------------------------------------------------------- expressions

// Precedence from IEC 61131-3 3rd edition table 71, tightest first.
expression
  : primary                                                     # primaryExpr
  | op=(MINUS | PLUS | NOT) expression                          # unaryExpr
  | expression POWER expression                                 # powerExpr
  | expression op=(STAR | SLASH | MOD) expression               # mulExpr
  | expression op=(PLUS | MINUS) expression                     # addExpr
  | expression op=(LT | GT | LE | GE) expression                # relExpr
  | expression op=(EQ | NE) expression                          # eqExpr
  | expression op=(AND | AMP | AND_THEN) expression             # andExpr
  | expression XOR expression                                   # xorExpr
  | expression op=(OR | OR_ELSE) expression                     # orExpr
  ;

primary
  : literal                                                     # literalPrimary
  | callee=variable LPAREN (callArg (COMMA callArg)*)? RPAREN callSuffix* # callPrimary
  // Operators written as standard functions (the ST OpenPLC writes for
  // FBD): AND(a, b, c), XOR(a, b), MOD(a, b). NOT(x) is the unary form.
  | op=(AND | OR | XOR | MOD) LPAREN callArg (COMMA callArg)* RPAREN # operatorCallPrimary
  | variable                                                    # variablePrimary
  // RuSTy's address operator: `&x` is REF(x).
  | AMP variable                                                # addressPrimary
  | LPAREN expression RPAREN                                    # parenPrimary
  ;

// A variable access: a name, a direct address, then fields, indices,
// bit accesses (`x.3`), partial accesses (IEC 61131-3 3rd edition:
// `x.%X3`, `x.%B1`, `x.%W0`, `x.%D1`) and dereferences (`p^`).
variable
  : (ident | DIRECT) selector*
  ;

selector
  : DOT ident                                                   # fieldSel
  | DOT INTEGER                                                 # bitSel
  | DOT DIRECT                                                  # partSel
  | LBRACKET expression (COMMA expression)* RBRACKET            # indexSel
  | CARET                                                       # derefSel
  ;

literal
  : INTEGER                                                     # intLiteral
  | REAL_LIT                                                    # realLiteral
  | (TRUE | FALSE)                                              # boolLiteral
  | DURATION                                                    # durationLiteral
  | (TOD_LIT | DATE_LIT | DT_LIT)                               # dateLiteral
  | (STRING_LIT | WSTRING_LIT)                                  # stringLiteral
  | type=(IDENT | STRING_KW | WSTRING_KW) HASH sign=(MINUS | PLUS)? (value=(INTEGER | REAL_LIT | TRUE | FALSE | STRING_LIT | WSTRING_LIT) | enumName=ident) # typedLiteral
  ;
